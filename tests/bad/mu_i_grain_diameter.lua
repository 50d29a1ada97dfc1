-- expect: mu_i_grain_diameter\.lua:4: material\.mu_i\{\}: d = 0 is out of range \(expected a value > 0\)
-- case: ranges | a mu(I) material with a zero grain diameter
local mpm = require "moraine"
local mat = mpm.material.mu_i{ density = 1470, E = 1e6, d = 0 }
