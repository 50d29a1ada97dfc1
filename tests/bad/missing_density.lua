-- expect: missing_density\.lua:4: material\.linear_elastic\{\}: parameter 'density' \(mass density\) is required
-- case: keys | a material without its density
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ E = 1e6, nu = 0.3 }
