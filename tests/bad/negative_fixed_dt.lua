-- expect: negative_fixed_dt\.lua:4: simulation\{\} dt: fixed = -0\.0001 is out of range \(expected a value > 0, in s\)
-- case: ranges | a negative fixed time step
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, dt = { fixed = -1e-4 } }
