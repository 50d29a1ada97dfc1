-- expect: missing_run_length\.lua:8: run\{\}: give time = <seconds>, end_time = <model time> and/or steps = <count>
-- case: keys | run{} with neither time nor steps
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat })
sim:run{ thermo = 10 }
