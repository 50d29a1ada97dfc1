-- expect: friction_angle_over_90\.lua:4: material\.mohr_coulomb\{\}: phi = 95 is out of range \(expected a value in \[0, 90\)\)
-- case: ranges | friction angle over 90 degrees
local mpm = require "moraine"
local mat = mpm.material.mohr_coulomb{ density = 2000, E = 1e6, nu = 0.3, phi = 95, cohesion = 0 }
