-- moraine robustness: the output disk fills up during a run (tests/robust/disk_full.sh).
-- A small block is run with VTK output and checkpointed; then a larger body is
-- added, whose next VTK file no longer fits under the file-size limit the test
-- sets with `ulimit -f`. The run must stop at that file with its path, and
-- everything written before must stay complete.
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 0.5}, cell = 0.05 }, gravity = {0, -9.81}, thermo = 0,
  output = { vtk = "part", every_steps = 5 } }
sim:add_particles(mpm.box{ min = {0.1, 0.0}, max = {0.3, 0.2} }, { material = mat })
sim:run{ steps = 20 }
sim:save("early.h5") -- in the output directory
-- a body 13 times larger: its snapshots no longer fit under the limit
sim:add_particles(mpm.box{ min = {0.4, 0.0}, max = {0.9, 0.45} }, { material = mat, per_axis = 3 })
sim:run{ steps = 20 }
