-- expect: watchdog_speed.lua:10: run\{\}: step 1 \(t = [0-9.e+-]+ s\): the watchdog stopped the run: particle [0-9]+ at \(.*\) moves at 200 m/s, 2 cells per step \(bound 1; h = 0\.05 m, dt = 0\.0005 s\); likely cause: a time step above the stability limit
-- case: runtime | a particle crossing two cells per step (soft material, 200 m/s, fixed dt): the watchdog's speed test
local mpm = require "moraine"
mpm.warnings{ ignore = { "dt_above_cfl" } }
-- c = sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu))) = 1 m/s for nu = 0: dt / CFL = (200 + 1) / 200 x 2 < 4
local mat = mpm.material.linear_elastic{ density = 1000, E = 1000, nu = 0 }
local sim = mpm.simulation{ dim = 2, grid = { size = {2, 1}, cell = 0.05 }, thermo = 0, dt = { fixed = 5e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat,
  velocity = function() return 200, 0 end })
sim:run{ steps = 5 }
