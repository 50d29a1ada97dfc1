-- expect: unknown_key.lua:4: simulation\{\}: unknown key 'shpae' \(did you mean 'shape'\?\)
-- case: keys | a misspelt option (`shpae`)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  shpae = "linear" }
