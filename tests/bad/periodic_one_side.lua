-- expect: periodic_one_side\.lua:4: simulation\{\} boundary: face xmin is periodic but xmax is not: both faces of an axis must be periodic
-- case: geometry | a periodic condition on one face only
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, boundary = { left = "periodic" } }
