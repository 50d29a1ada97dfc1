-- expect: add_particles_in_step\.lua:9: add_particles\(\): not allowed inside a callback of this simulation's run\{\} \(a step is under way\); particles may be added from a hook \(sim:hook\{\.\.\.\}\) or stop_when, between steps, or after run\{\} returns
-- case: runtime | adding particles from a time-step function, inside a step
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
-- a dt function runs before each step is taken: too late to change the particles
sim:set_dt(function(s)
  s:add_particles(mpm.box{ min = {0.6, 0.6}, max = {0.8, 0.8} }, { material = mat })
  return 1e-4
end)
sim:run{ steps = 3 }
