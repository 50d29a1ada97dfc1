-- expect: region_seeds_nothing\.lua:6: add_particles\(\): the region seeds no particle on this grid \(is it inside the domain\?\)
-- case: geometry | a region that seeds no particle
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = {0.21, 0.21}, max = {0.22, 0.22} }, { material = mat })
