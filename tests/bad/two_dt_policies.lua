-- expect: two_dt_policies\.lua:4: simulation\{\} dt: give exactly one of fixed, a_tau, cfl, grid_cfl or fn \(got 2\)
-- case: keys | two time-step policies at once
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, dt = { fixed = 1e-4, a_tau = 0.1 } }
