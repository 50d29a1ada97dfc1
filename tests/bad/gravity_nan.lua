-- expect: gravity_nan\.lua:4: simulation\{\}: gravity\[2\] = NaN is out of range \(expected a finite value, in m/s\^2\)
-- case: types | a NaN inside a vector
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, gravity = {0, 0/0} }
