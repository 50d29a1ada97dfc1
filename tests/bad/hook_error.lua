-- expect: hook_error.lua:9: attempt to perform arithmetic on a nil value
-- case: runtime | an error inside a hook
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, gravity = {0, -9.81},
  output = { vtk = "frames", every_steps = 5 }, thermo = 0 }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mat })
sim:hook{ every_steps = 12, fn = function(s)
  local missing = s:time() + nothing_here
end }
sim:run{ steps = 100 }
