-- expect: body_density_zero\.lua:5: add_wall\{\}: density = 0 is out of range \(expected a value > 0, in kg/m\^3\)
-- case: ranges | a rigid body of zero density
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "footing", shape = "box", min = {0.2, 0.5}, max = {0.8, 0.6}, density = 0 }
