-- expect: size_not_whole_cells\.lua:4: simulation\{\}: grid: size 1 along axis 1 is not a whole number of cells of 0\.3 \(3\.333333 cells\)
-- case: geometry | a domain that is not a whole number of cells
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.3 } }
