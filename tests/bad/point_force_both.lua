-- expect: point_force_both.lua:6: point_force\{\}: give exactly one of force and traction
-- case: keys | a point load given both as a force and as a traction
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 } }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.8, 0.8 } }, { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 } })
sim:point_force{ region = mpm.box{ min = { 0.7, 0.7 }, max = { 0.8, 0.8 } }, force = { 0, -1 }, traction = { 0, -1 } }
