-- expect: run_checkpoint_no_interval\.lua:7: run\{\} checkpoint: give every = <steps> and/or wall = <seconds>
-- case: keys | run{ checkpoint = {} } without every or wall
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 2, checkpoint = { keep = 3 } }
