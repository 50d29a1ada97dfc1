-- expect: body_fix_unknown\.lua:5: add_wall\{\}: fix = 'theta' is not valid; valid: 'x', 'y', 'rz'
-- case: choices | an unknown degree of freedom to fix
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
sim:add_wall{ name = "footing", shape = "box", min = {0.2, 0.5}, max = {0.8, 0.6}, density = 2400, fix = { "x", "theta" } }
