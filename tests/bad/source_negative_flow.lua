-- expect: source_negative_flow\.lua:7: add_source\{\}: source 'inlet': velocity: the inflow velocity -0\.1 m/s along x at t = 0 s points out of the inlet \(a negative flow\)
-- case: ranges | an inflow source whose velocity points out of its inflow face
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 0.4}, cell = 0.05 }, thermo = 0, diagnostics = false, series = false }
-- face = "xmin": the material enters through x = 0 and must move towards +x
sim:add_source{ name = "inlet", region = mpm.box{ min = {0, 0}, max = {0.1, 0.4} }, material = mat, face = "xmin",
  velocity = {-0.1, 0} }
