-- expect: sort_every_negative\.lua:4: simulation\{\}: sort_every = -5 is out of range
-- case: ranges | a negative interval between particle reorderings
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, sort_every = -5 }
