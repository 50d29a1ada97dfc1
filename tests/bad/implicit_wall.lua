-- expect: implicit_wall\.lua:7: implicit\{\}: implicit: the simulation has rigid walls \(sim:add_wall\), which the implicit integrator does not take
-- case: choices | a rigid wall under the implicit integrator
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "linear" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mpm.material.hencky{ density = 1, E = 1e3 } })
sim:add_wall{ name = "floor", shape = "plane", point = {0, 0.1}, normal = {0, 1} }
local imp = sim:implicit{ dt = 0.01 }
