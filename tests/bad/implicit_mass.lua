-- expect: implicit_mass.lua:6: implicit\{\}: mass = 'consistant' is not valid \(did you mean 'consistent'\?\)
-- case: choices | implicit{} with a misspelt mass matrix kind
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mpm.material.hencky{ density = 1, E = 1e3 } })
local imp = sim:implicit{ mass = "consistant" }
