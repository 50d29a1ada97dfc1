-- expect: bad_boundary.lua:4: simulation\{\} boundary: bottom = 'frction' is not valid \(did you mean 'friction'\?\)
-- case: choices | a misspelt boundary kind
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  boundary = { bottom = { "frction", mu = 0.3 } } }
