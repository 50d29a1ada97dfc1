-- expect: output_format_unknown\.lua:4: simulation\{\} output: format = 'hdf5' is not valid; valid: 'binary', 'ascii', 'vtkhdf'
-- case: choices | an output format moraine does not write
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, output = { vtk = "p", format = "hdf5" } }
