-- expect: implicit_material.lua:6: implicit\{\}: implicit: material 'linear_elastic' \(linear_elastic\) has no implicit form; materials with one: von_mises, hencky \(doc/implicit.md\)
-- case: choices | implicit{} on a material the implicit integrator does not model
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mpm.material.linear_elastic{ density = 1, E = 1e3 } })
local imp = sim:implicit{ dt = 0.01 }
