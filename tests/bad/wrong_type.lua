-- expect: wrong_type.lua:3: simulation\{\} grid: cell must be a number, got string
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = "0.1" } }
