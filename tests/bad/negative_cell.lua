-- expect: negative_cell.lua:4: simulation\{\} grid: cell = -0.1 is out of range \(expected a value > 0, in m\)
-- case: ranges | a negative cell size
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = -0.1 } }
