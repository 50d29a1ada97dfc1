-- expect: run_after_invalid_state\.lua:9: run\{\}: the simulation stopped at step 5 on a state its grid cannot hold \(a particle outside it\); load an earlier checkpoint to go on
-- case: runtime | running on after a run stopped with a particle outside the grid
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false,
  series = false, boundary = { all = "free" }, dt = { fixed = 1e-3 }, name = "leaving" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat, velocity = {-50, 0} })
assert(not pcall(sim.run, sim, { steps = 100 }))
sim:run{ steps = 1 }
