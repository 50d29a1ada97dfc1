-- expect: body_plane\.lua:5: add_wall\{\}: density: wall 'floor' is unbounded \(infinite mass\)
-- case: geometry | a plane wall given a density (a body of infinite mass)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "floor", shape = "plane", point = {0, 0.2}, normal = {0, 1}, density = 2400 }
