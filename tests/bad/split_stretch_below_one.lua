-- expect: split_stretch_below_one\.lua:4: simulation\{\} split: stretch = 0\.8 is out of range \(expected a value > 1\)
-- case: ranges | a splitting threshold at which unstretched particles would split
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, split = { stretch = 0.8 } }
