-- expect: method_misspelt\.lua:6: simulation has no method 'ad_particles' \(did you mean 'add_particles'\?\)
-- case: keys | a misspelt simulation method (`sim:ad_particles`)
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:ad_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
