-- expect: poisson_below\.lua:4: material\.linear_elastic\{\}: nu = -1\.2 is out of range \(expected a value in \(-1, 0\.5\)\)
-- case: ranges | Poisson ratio below -1
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = -1.2 }
