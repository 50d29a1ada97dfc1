-- expect: negative_cell.lua:3: simulation\{\} grid: cell = -0.1 is out of range \(expected a value > 0, in m\)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = -0.1 } }
