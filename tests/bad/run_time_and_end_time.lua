-- expect: run_time_and_end_time\.lua:7: run\{\}: give time \(to advance\) or end_time \(to end at\), not both
-- case: keys | run{} with both time and end_time
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ time = 0.1, end_time = 0.2 }
