-- expect: negative_friction\.lua:4: simulation\{\} boundary: mu = -0\.3 is out of range \(expected a value >= 0\)
-- case: ranges | a negative wall friction coefficient
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, boundary = { bottom = { kind = "friction", mu = -0.3 } } }
