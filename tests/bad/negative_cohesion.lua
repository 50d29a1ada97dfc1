-- expect: negative_cohesion\.lua:4: material\.mohr_coulomb\{\}: cohesion = -5 is out of range \(expected a value >= 0\)
-- case: ranges | negative cohesion
local mpm = require "moraine"
local mat = mpm.material.mohr_coulomb{ density = 2000, E = 1e6, nu = 0.3, phi = 30, cohesion = -5 }
