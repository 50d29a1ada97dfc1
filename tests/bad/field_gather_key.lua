-- expect: field_gather_key.lua:5: field\(\): unknown key 'gathr' \(did you mean 'gather'\?\)
-- case: keys | a misspelt option of sim:field
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0 }
sim:field("mass", { gathr = true })
