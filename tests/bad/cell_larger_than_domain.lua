-- expect: cell_larger_than_domain\.lua:4: simulation\{\}: grid: cell size 2 is larger than the domain size 1 along axis 1
-- case: geometry | a cell size larger than the domain
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 2 } }
