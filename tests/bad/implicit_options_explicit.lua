-- expect: implicit_options_explicit.lua:4: simulation\{\}: implicit: the implicit integrator's options need integrator = "implicit"
-- case: keys | implicit integrator options on a simulation that keeps the explicit step
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, implicit = { ghost = 0.1 } }
