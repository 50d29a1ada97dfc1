-- expect: unknown_key.lua:3: simulation\{\}: unknown key 'shpae' \(did you mean 'shape'\?\)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  shpae = "linear" }
