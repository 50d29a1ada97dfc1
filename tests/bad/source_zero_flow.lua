-- expect: source_zero_flow\.lua:6: add_source\{\}: velocity: the inflow velocity is zero \(no flow\)
-- case: ranges | an inflow source with zero velocity
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 0.4}, cell = 0.05 }, thermo = 0, diagnostics = false, series = false }
sim:add_source{ region = mpm.box{ min = {0, 0}, max = {0.1, 0.4} }, material = mat, velocity = {0, 0} }
