-- expect: watchdog_energy.lua:12: run\{\}: step 11 \(t = [0-9.e+-]+ s\): the watchdog stopped the run: the energy the discretisation created, W_MPM = [0-9.e+]+ J, is [0-9.e+]+ times the energy scale [0-9.e+]+ J \(bound 1;.*likely cause: a time step above the stability limit.*the state at step 11 is in
-- case: runtime | the same explosive run with the dt test off: W_MPM beyond the energy scale
local mpm = require "moraine"
mpm.warnings{ ignore = { "dt_above_cfl" } }
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e15, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, gravity = {0, -9.81}, thermo = 0,
  boundary = { all = "slip" }, watchdog = { dt = 0 } }
-- a block in the corner: the slip walls clamp it (its velocity stays 0) while
-- its elastic energy grows without bound
sim:add_particles(mpm.box{ min = {0, 0}, max = {0.4, 0.2} }, { material = mat })
sim:set_dt{ fixed = 2300 * sim:dt_estimate().cfl }
sim:run{ steps = 300 }
