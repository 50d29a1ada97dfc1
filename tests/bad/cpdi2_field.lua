-- expect: cpdi2_field\.lua:8: run\{\}: shape = 'cpdi2': the particle field 'cpdi2_corners' exists without its 8 components: the name is CPDI2's
-- case: runtime | a deck's particle field under the name CPDI2 keeps its corners in
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "cpdi2" }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} },
                  { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 } })
sim:particle_field{ name = "cpdi2_corners", components = 1 }
sim:run{ steps = 1 }
