-- expect: bad_boundary.lua:3: simulation\{\} boundary: bottom = 'frction' is not valid \(did you mean 'friction'\?\)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  boundary = { bottom = { "frction", mu = 0.3 } } }
