-- expect: negative_density\.lua:4: material\.linear_elastic\{\}: density = -1000 is out of range \(expected a value > 0\)
-- case: ranges | negative density
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = -1000, E = 1e6, nu = 0.3 }
