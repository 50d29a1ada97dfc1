-- expect: dt_function_nan\.lua:7: run\{\}: step 1: the function time-step policy gave dt = NaN \(must be > 0\)
-- case: runtime | a time-step function returning NaN (spelt NaN in every message)
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false, dt = function(s) return 0 / 0 end }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 5 }
