-- expect: zero_young\.lua:4: material\.neo_hookean\{\}: E = 0 is out of range \(expected a value > 0\)
-- case: ranges | zero Young modulus
local mpm = require "moraine"
local mat = mpm.material.neo_hookean{ density = 1000, E = 0, nu = 0.3 }
