-- expect: --restart: 'no_such_checkpoint\.h5': cannot open: No such file or directory
-- options: --restart no_such_checkpoint.h5
-- case: files | --restart naming a file that does not exist
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 2 }
