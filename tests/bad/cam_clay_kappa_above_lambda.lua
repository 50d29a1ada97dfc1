-- expect: cam_clay_kappa_above_lambda\.lua:4: material\.cam_clay\{\}: kappa = 0\.3 must be below lambda = 0\.2 \(no plastic hardening otherwise\)
-- case: ranges | a Modified Cam-Clay material whose swelling slope kappa exceeds the compression slope lambda
local mpm = require "moraine"
local mat = mpm.material.cam_clay{ density = 1800, M = 1.2, lambda = 0.2, kappa = 0.3, v0 = 2, p_c0 = 2e5 }
