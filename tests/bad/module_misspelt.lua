-- expect: module_misspelt\.lua:5: mpm has no function 'boxx' \(did you mean 'box'\?\)
-- case: keys | a misspelt module function (`mpm.boxx`)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local block = mpm.boxx{ min = {0.2, 0.2}, max = {0.4, 0.4} }
