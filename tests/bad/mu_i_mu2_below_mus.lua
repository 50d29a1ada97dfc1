-- expect: mu_i_mu2_below_mus\.lua:4: material\.mu_i\{\}: mu_2 = 0\.3 must exceed mu_s = 0\.381863 \(mu\(I\) rises from mu_s to mu_2\)
-- case: ranges | a mu(I) material whose limiting friction mu_2 is below the static friction mu_s
local mpm = require "moraine"
local mat = mpm.material.mu_i{ density = 1470, E = 1e6, mu_2 = 0.3 }
