-- expect: XX
-- case: ranges | a plane wall with a zero normal
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "floor", shape = "plane", point = {0, 0.2}, normal = {0, 0} }
