-- expect: source_negative_function\.lua:10: run\{\}: source 'inlet': velocity: the inflow velocity -0\.05 m/s along x at t = 0\.[0-9]+ s points out of the inlet \(a negative flow\)
-- case: runtime | an inflow velocity function that turns negative during the run
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 0.4}, cell = 0.05 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = {0.5, 0}, max = {0.6, 0.1} }, { material = mat })
-- the flow reverses after 1 ms
sim:add_source{ name = "inlet", region = mpm.box{ min = {0, 0}, max = {0.1, 0.4} }, material = mat, face = "xmin",
  velocity = function(t) return t < 1e-3 and 0.1 or -0.05, 0 end }
sim:run{ time = 0.01 }
