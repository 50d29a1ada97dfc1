-- expect: flip_fraction_range\.lua:4: simulation\{\} scheme: flip_fraction = 1\.5 is out of range \(expected a value in \[0, 1\]\)
-- case: ranges | a FLIP fraction above 1
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, scheme = { transfer = "FLIP", flip_fraction = 1.5 } }
