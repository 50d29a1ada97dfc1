-- expect: import_other_dim.lua:10: import\(\): '.*flat.h5': the checkpoint is 2D but the simulation is 3D
-- case: files | importing a 2D checkpoint into a 3D simulation
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local flat = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, thermo = 0, diagnostics = false }
flat:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.6, 0.6 } }, { material = mat })
local path = flat:save("flat.h5")
local cube = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 1 }, cell = 0.1 }, thermo = 0, diagnostics = false }
cube:add_particles(mpm.box{ min = { 0.2, 0.2, 0.2 }, max = { 0.4, 0.4, 0.4 } }, { material = mat })
local before = cube:particle_count()
local ok, err = pcall(function() cube:import(path) end)
assert(not ok and cube:particle_count() == before, "the failed import changed the simulation")
error(err, 0)
