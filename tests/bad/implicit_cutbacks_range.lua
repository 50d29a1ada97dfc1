-- expect: implicit_cutbacks_range.lua:6: implicit\{\}: cutbacks = 11 is out of range \(expected a value in \[0, 10\]\)
-- case: ranges | implicit cutbacks above the limit of 10 halvings
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.4, 0.4 } }, { material = mpm.material.hencky{ density = 1, E = 1, nu = 0.3 } })
local imp = sim:implicit{ dt = 0.1, cutbacks = 11 }
