-- expect: run_end_time_past\.lua:8: run\{\}: end_time = 0\.0001 is not after the simulation.s time t = 0\.0002 s
-- case: ranges | run{ end_time } at or before the current model time
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 2 }
sim:run{ end_time = 1e-4 }
