-- expect: material_not_material\.lua:6: add_particles\(\): expected a material \(mpm\.material\.<model>\{\.\.\.\}\), got table
-- case: types | a plain table given as the material
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = { density = 1000 } })
