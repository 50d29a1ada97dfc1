-- expect: load_outside_state\.lua:9: load\(\): '.*/leaving_failed\.h5': /particles/x: particle 0 \(id 1\) at \(-0\.0288675, 0\.221132, 0\) lies outside the grid
-- case: files | a checkpoint whose particle lies outside its grid (the state a failed run leaves)
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false,
  series = false, boundary = { all = "free" }, dt = { fixed = 1e-3 }, name = "leaving" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat, velocity = {-50, 0} })
assert(not pcall(sim.run, sim, { steps = 100 }))
local again = mpm.load(mpm.outdir .. "/leaving_failed.h5")
