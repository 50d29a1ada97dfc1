-- expect: callback_bad_return\.lua:7: add_particles\(\): velocity function must return 2 numbers \(or a table of them\) at \(0\.221132, 0\.221132, 0\)
-- case: runtime | an initial-velocity function returning a string
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat, velocity = function(x, y) return "fast", 0 end })
