-- expect: save_under_file\.lua:9: save\(\): cannot write '.*/plain/state\.h5': Not a directory
-- case: files | saving under a path whose directory is a file
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat })
local f = assert(io.open(mpm.outdir .. "/plain", "w")) f:close()
sim:save(mpm.outdir .. "/plain/state.h5")
