-- expect: region_not_region\.lua:6: add_particles\(\): expected a region \(mpm\.box\{\.\.\.\}, mpm\.disk\{\.\.\.\}, \.\.\.\), got table
-- case: types | a plain table given as the region
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles({ min = {0, 0}, max = {1, 1} }, { material = mat })
