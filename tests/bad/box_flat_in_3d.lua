-- expect: box_flat_in_3d\.lua:6: add_particles\(\): the region has no extent along z \(z from 0 to 0\), so it seeds nothing in a 3D simulation \(a box needs min and max of 3 components\)
-- case: geometry | a 2D box (min and max of 2 components) in a 3D simulation
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 3, grid = { size = {1, 1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.5, 0.5} }, { material = mat })
