-- expect: outside_grid.lua:6: add_particles\(\): region extends outside the grid
-- case: geometry | a region that reaches outside the grid
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_particles(mpm.box{ min = {0.5, 0.5}, max = {1.5, 0.9} }, { material = mat })
