-- expect: wall_mu_missing\.lua:5: add_wall\{\}: mu: a friction wall needs mu
-- case: keys | a friction wall without mu
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "floor", shape = "plane", point = {0, 0.2}, normal = {0, 1}, kind = "friction" }
