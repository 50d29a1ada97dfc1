-- expect: dt_below_min\.lua:8: run\{\}: step 1 \(t = 0 s\): the time step collapsed to 1e-09 s, below the minimum 1e-06 s; the state at step 0 is in .*/simulation_failed\.h5
-- case: runtime | a time step collapsing below its minimum
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false, dt = { fn = function(s) return 1e-9 end, min = 1e-6 } }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat })
sim:run{ steps = 3 }
