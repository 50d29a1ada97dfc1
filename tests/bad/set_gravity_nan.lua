-- expect: set_gravity_nan\.lua:6: set_gravity\(\): gravity\[1\] = NaN is out of range \(expected a finite value, in m/s\^2\)
-- case: ranges | a NaN given to a setter, refused as simulation{} refuses it
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:set_gravity{ 0 / 0, -9.81 }
