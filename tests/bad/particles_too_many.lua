-- expect: particles_too_many\.lua:7: add_particles\(\): up to 1\.12e\+09 particles \(the seeding points of the region's bounding box\) need [0-9.]+ GB, more than this machine's [0-9.]+ GB of memory \(fewer particles per cell, a coarser grid or a smaller region\?\)
-- case: geometry | more particles than the machine's memory holds (1.1e9, about 450 GB), refused before seeding
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
-- a legal grid of 2.2 million cells, filled at 512 particles per cell
local sim = mpm.simulation{ dim = 3, grid = { size = { 1.3, 1.3, 1.3 }, cell = 0.01 }, thermo = 0, diagnostics = false }
sim:add_particles(mpm.box{ min = { 0, 0, 0 }, max = { 1.3, 1.3, 1.3 } }, { material = mat, per_axis = 8 })
