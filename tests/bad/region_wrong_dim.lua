-- expect: region_wrong_dim\.lua:6: add_particles\(\): this region is 2D only, the simulation is 3D
-- case: geometry | a 2D-only region in a 3D simulation
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 3, grid = { size = {1, 1, 1}, cell = 0.25 } }
sim:add_particles(mpm.polygon{ vertices = { {0.1, 0.1}, {0.5, 0.1}, {0.3, 0.5} } }, { material = mat })
