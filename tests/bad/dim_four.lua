-- expect: dim_four\.lua:4: simulation\{\}: dim = 4 is out of range \(expected a value in \[2, 3\]\)
-- case: ranges | dimension 4
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 4, grid = { size = {1, 1}, cell = 0.1 } }
