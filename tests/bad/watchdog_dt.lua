-- expect: watchdog_dt.lua:11: run\{\}: step 1 \(t = [0-9.e+-]+ s\): the watchdog stopped the run: the step dt = [0-9.e+-]+ s is 2\.3e\+03 times the particle CFL estimate .*likely cause: a time step above the stability limit.*the state at step 1 is in
-- case: runtime | an explosive run against walls (E = 1e15 Pa, dt 2300x the CFL estimate): the watchdog's dt test
local mpm = require "moraine"
mpm.warnings{ ignore = { "dt_above_cfl" } }
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e15, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, gravity = {0, -9.81}, thermo = 0,
  boundary = { all = "slip" } }
-- a block in the corner: the slip walls clamp it, so nothing turns non-finite
sim:add_particles(mpm.box{ min = {0, 0}, max = {0.4, 0.2} }, { material = mat })
sim:set_dt{ fixed = 2300 * sim:dt_estimate().cfl }
sim:run{ steps = 300 }
