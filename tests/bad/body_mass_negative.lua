-- expect: body_mass_negative\.lua:5: add_wall\{\}: mass = -5 is out of range \(expected a value > 0, in kg\)
-- case: ranges | a rigid body of negative mass
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "gate", shape = "cylinder", center = {0.5, 0.5}, radius = 0.1, mass = -5 }
