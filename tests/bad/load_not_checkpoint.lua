-- expect: load_not_checkpoint\.lua:9: load\(\): '.*/series\.h5': not a moraine checkpoint \(format is 'moraine-series'\)
-- case: files | an HDF5 file that is not a moraine checkpoint
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, series = "series.h5", diagnostics = false }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 2 }
sim = nil collectgarbage()
local other = mpm.load(mpm.outdir .. "/series.h5")
