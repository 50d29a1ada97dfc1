-- expect: cpdi_wls.lua:7: run\{\}: shape = 'cpdi' takes shape_boundary = 'extended' only, not 'wls'
-- case: runtime | CPDI with a face treatment other than `extended`
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "cpdi", shape_boundary = "wls" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} },
                  { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 } })
sim:run{ steps = 1 }
