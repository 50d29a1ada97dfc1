-- expect: wrong_type.lua:4: simulation\{\} grid: cell must be a number, got string
-- case: types | a string where a number is expected
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = "0.1" } }
