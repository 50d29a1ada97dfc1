-- expect: per_cell_not_square\.lua:7: add_particles\(\): per_cell = 3 is not a square number \(use 1, 4, 9, 16, \.\.\. in 2D; 1, 8, 27, \.\.\. in 3D\)
-- case: ranges | a per-cell count that is not a square in 2D
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat, per_cell = 3 })
