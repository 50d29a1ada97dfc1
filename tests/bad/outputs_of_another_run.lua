-- expect: outputs_of_another_run\.lua:9: run\{\}: the output directory '.*' holds this simulation's outputs of another run: '.*/diagnostics\.csv'; use another output directory \(-o\), remove them, pass --overwrite to replace them, or --restart CHECKPOINT to continue that run
-- case: files | a run into a directory holding another run's outputs
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
-- what an earlier run left
local f = assert(io.open(mpm.outdir .. "/diagnostics.csv", "w")) f:write("step,time\n") f:close()
sim:run{ steps = 2 }
