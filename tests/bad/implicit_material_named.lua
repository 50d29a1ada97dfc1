-- expect: implicit_material_named.lua:9: implicit\{\}: implicit: material 'sand' \(mohr_coulomb\) has no implicit form; materials with one: von_mises, hencky
-- case: choices | implicit{} on a named material of a model without an implicit form (the message names both)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
local clay = mpm.material.hencky{ density = 1, E = 1e3, name = "clay" }
local sand = mpm.material.mohr_coulomb{ density = 1, E = 1e3, nu = 0.3, phi = 30, psi = 0, cohesion = 1, name = "sand" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = clay })
sim:add_particles(mpm.box{ min = {0.2, 0.6}, max = {0.6, 0.8} }, { material = sand })
local imp = sim:implicit{ dt = 0.01 }
