-- expect: stop_when_error\.lua:8: simulation has no method 'nothing'
-- case: runtime | an error inside stop_when
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat })
sim:run{ steps = 5, stop_when = function(s) return s.nothing.here end }
