-- expect: contact_holds\.lua:10: run\{\}: .*contact: scheme holds = 'particles' is not available with contact between bodies
-- case: other | FLIP taking the holds of V asked for with contact between bodies
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, scheme = { transfer = "FLIP", holds = "particles" } }
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat, body = "a" })
sim:add_particles(mpm.box{ min = {0.5, 0.2}, max = {0.7, 0.4} }, { material = mat, body = "b" })
sim:add_contact{ bodies = { "a", "b" }, mu = 0.3 }
-- the step refuses it
sim:run{ steps = 1 }
