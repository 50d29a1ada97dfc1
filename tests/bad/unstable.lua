-- expect: unstable.lua:11: run\{\}: step [0-9]+.*particle [0-9]+.*(non-finite|invert|left the grid).*the state at step [0-9]+ is in
-- case: runtime | a run with a fixed dt 15x above the CFL estimate (robust.unstable_cfl: exactly 10x)
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e8, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, gravity = {0, -9.81},
  dt = { fixed = 2e-3 }, thermo = 0, watchdog = false, output = { vtk = "unstable", every_steps = 20 } }
sim:add_particles(mpm.box{ min = {0.2, 0.0}, max = {0.6, 0.5} }, { material = mat,
  velocity = function(x, y) return 0, -5 * y end })
-- dt is far above the CFL limit h / c = 1.6e-4 s; without the watchdog (which
-- stops such a run at its first step: bad.watchdog_dt) the state check fires
sim:run{ steps = 2000 }
