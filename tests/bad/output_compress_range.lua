-- expect: output_compress_range\.lua:4: simulation\{\} output: compress = 10 is out of range \(expected a value in \[0, 9\]\)
-- case: ranges | a zlib level above 9
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, output = { vtk = "p", compress = 10 } }
