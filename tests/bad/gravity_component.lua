-- expect: gravity_component\.lua:4: simulation\{\}: gravity\[2\] must be a number, got string
-- case: types | a string inside a vector
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, gravity = {0, "g"} }
