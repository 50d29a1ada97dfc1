-- expect: material_unknown_key\.lua:4: material\.mohr_coulomb\{\}: unknown parameter 'cohesoin' \(did you mean 'cohesion'\?\)
-- case: keys | a misspelt material parameter
local mpm = require "moraine"
local mat = mpm.material.mohr_coulomb{ density = 2000, E = 1e6, nu = 0.3, phi = 30, cohesoin = 10 }
