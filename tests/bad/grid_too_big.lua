-- expect: grid_too_big\.lua:5: simulation\{\}: grid: [0-9]+ nodes need [0-9.]+ GB, more than this machine's [0-9.]+ GB of memory \(is the cell size right\?\)
-- case: geometry | a legal grid whose arrays need more memory than the machine has (3.4e8 nodes, 52 GB)
local mpm = require "moraine"
-- a cell size typed a hundred times too small
local sim = mpm.simulation{ dim = 3, grid = { size = { 7, 7, 7 }, cell = 0.01 }, thermo = 0, diagnostics = false }
