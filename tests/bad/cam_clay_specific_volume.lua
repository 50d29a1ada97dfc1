-- expect: cam_clay_specific_volume\.lua:4: material\.cam_clay\{\}: v0 = 0\.8 is out of range \(expected a value >= 1\)
-- case: ranges | a Modified Cam-Clay material with a specific volume below 1 (a negative void ratio)
local mpm = require "moraine"
local mat = mpm.material.cam_clay{ density = 1800, M = 1.2, lambda = 0.2, kappa = 0.04, v0 = 0.8, p_c0 = 2e5 }
