-- expect: mass_scaling_range\.lua:5: simulation\{\}: mass_scaling = 0\.5 is out of range \(expected a value in \[1, 1e\+12\]\)
-- case: ranges | a mass scaling factor below 1
local mpm = require "moraine"
-- the factor multiplies the inertial mass: below 1 it would only shorten the stable step
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, mass_scaling = 0.5 }
