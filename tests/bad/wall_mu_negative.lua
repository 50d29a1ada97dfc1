-- expect: wall_mu_negative\.lua:5: add_wall\{\}: mu = -0\.3 is out of range \(expected a value >= 0\)
-- case: ranges | a friction wall with a negative mu
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "floor", shape = "plane", point = {0, 0.2}, normal = {0, 1}, kind = "friction", mu = -0.3 }
