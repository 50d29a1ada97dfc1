-- expect: scheme_holds\.lua:4: simulation\{\} scheme: holds = 'particle' is not valid \(did you mean 'particles'\?\)
-- case: choices | a misspelt scheme holds
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  scheme = { transfer = "FLIP", holds = "particle" } }
