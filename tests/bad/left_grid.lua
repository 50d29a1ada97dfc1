-- expect: left_grid\.lua:8: run\{\}: step 5 \(t = 0\.005 s\): particle 1 left the grid at \(-0\.0288675, 0\.221132, 0\) with velocity .*
-- case: runtime | a particle leaving the grid through a free face
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false, boundary = { all = "free" }, dt = { fixed = 1e-3 } }
local box = mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }
sim:add_particles(box, { material = mat, velocity = {-50, 0} })
sim:run{ steps = 100 }
