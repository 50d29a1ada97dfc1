-- expect: material_model_misspelt\.lua:4: mpm\.material has no model 'linear_elatic' \(did you mean 'linear_elastic'\?\)
-- case: keys | a misspelt material model (`mpm.material.linear_elatic`)
local mpm = require "moraine"
local mat = mpm.material.linear_elatic{ density = 1000, E = 1e6, nu = 0.3 }
