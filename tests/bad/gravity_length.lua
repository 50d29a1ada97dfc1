-- expect: gravity_length\.lua:4: simulation\{\}: gravity must have 2 components \(the simulation is 2D\), got 3
-- case: types | a 3-component gravity in a 2D simulation
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, gravity = {0, -9.81, 0} }
