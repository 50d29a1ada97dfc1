-- expect: contact_one_body\.lua:7: add_contact\{\}: contact: there is no body 'b' \(name it in add_particles\{body = "b"\} first; contact needs two bodies\)
-- case: other | contact asked for with only one body
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 } }
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mat, body = "a" })
sim:add_contact{ bodies = { "a", "b" }, mu = 0.3 }
