-- expect: scheme_volumetric\.lua:4: simulation\{\} scheme: volumetric = 'Fbar' is not valid \(did you mean 'fbar'\?\)
-- case: choices | a misspelt scheme volumetric
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  scheme = { transfer = "TPIC", volumetric = "Fbar" } }
