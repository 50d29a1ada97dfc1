-- expect: cpdi2_split\.lua:7: run\{\}: shape = 'cpdi2' does not take split \(splitting halves the parallelogram F U0, not the tracked corners\): use shape = 'cpdi' with split, or cpdi2 without
-- case: runtime | CPDI2 with particle splitting
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "cpdi2", split = { stretch = 1.5 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} },
                  { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 } })
sim:run{ steps = 1 }
