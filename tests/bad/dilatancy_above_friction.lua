-- expect: dilatancy_above_friction\.lua:4: material\.drucker_prager\{\}: psi = 30 deg exceeds phi = 20 deg \(the flow would create energy\)
-- case: ranges | dilatancy angle above the friction angle
local mpm = require "moraine"
local mat = mpm.material.drucker_prager{ density = 2000, E = 1e6, nu = 0.3, phi = 20, psi = 30, cohesion = 0 }
