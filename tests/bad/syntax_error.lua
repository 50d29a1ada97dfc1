-- expect: syntax_error.lua:6: .*expected
-- case: syntax | a Lua syntax error in the deck
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_particles(mpm.box{ min = {0, 0}, max = {0.5, 0.5} } { material = mat )
