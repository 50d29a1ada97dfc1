-- expect: implicit_ghost.lua:6: implicit\{\}: implicit: ghost penalty: only the linear and gimp shape functions \(hat grid basis\) are supported, not 'quadratic_bspline'
-- case: choices | the ghost penalty with quadratic B-splines (it is written for the hat basis)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "quadratic_bspline" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mpm.material.hencky{ density = 1, E = 1e3 } })
local imp = sim:implicit{ dt = 0.01, ghost = 0.1 }
