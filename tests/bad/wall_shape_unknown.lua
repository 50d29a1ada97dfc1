-- expect: wall_shape_unknown\.lua:5: add_wall\{\}: shape = 'sphere' is not valid
-- case: choices | a wall of an unknown shape
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "w", shape = "sphere", point = {0, 0.2}, normal = {0, 1} }
