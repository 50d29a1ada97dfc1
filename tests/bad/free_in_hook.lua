-- expect: free_in_hook\.lua:8: free\(\): not allowed inside a hook or callback of this simulation's run\{\} \(call it after run\{\} returns\)
-- case: runtime | freeing a simulation inside its own hook
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat })
sim:hook{ every_steps = 1, fn = function(s) s:free() end }
sim:run{ steps = 3 }
