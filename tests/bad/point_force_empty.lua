-- expect: point_force_empty.lua:6: point_force\{\}: region: holds no material point
-- case: geometry | a point load on a region without material points
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 } }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.8, 0.8 } }, { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 } })
sim:point_force{ region = mpm.box{ min = { 0.9, 0.9 }, max = { 1, 1 } }, force = { 0, -1 } }
