-- expect: density_boolean\.lua:4: material\.linear_elastic\{\}: density must be a number \(mass density, kg/m\^3\), got boolean
-- case: types | a boolean where a number is expected
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = true, E = 1e6, nu = 0.3 }
