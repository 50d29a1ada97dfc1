-- expect: source_outside\.lua:7: add_source\{\}: source 'inlet': region: the inlet box \[-0\.1, 0\.1\] along x is outside the grid \[0, 1\]
-- case: geometry | an inflow source whose inlet box reaches outside the grid
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 0.4}, cell = 0.05 }, thermo = 0, diagnostics = false, series = false }
-- the inflow plane must lie in the grid: the reservoir behind it is the source's own
sim:add_source{ name = "inlet", region = mpm.box{ min = {-0.1, 0}, max = {0.1, 0.4} }, material = mat, velocity = {0.1, 0} }
