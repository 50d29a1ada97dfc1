-- expect: on_leave_unknown\.lua:5: simulation\{\}: on_leave = 'remove' is not valid; valid: 'stop', 'delete'
-- case: choices | a misspelt policy for particles leaving the grid
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false,
  on_leave = "remove" }
