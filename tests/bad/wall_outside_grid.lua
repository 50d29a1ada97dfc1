-- expect: wall_outside_grid\.lua:5: add_wall\{\}: wall 'post' lies entirely outside the grid
-- case: geometry | a wall entirely outside the grid
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "post", shape = "cylinder", center = {3, 3}, radius = 0.5 }
