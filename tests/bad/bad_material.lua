-- expect: bad_material.lua:4: material.linear_elastic\{\}: nu = 0.5 is out of range \(expected a value in \(-1, 0.5\)\)
-- case: ranges | Poisson ratio of 0.5 (incompressible, outside (-1, 0.5))
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.5 }
