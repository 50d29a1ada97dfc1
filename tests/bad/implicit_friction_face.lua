-- expect: implicit_friction_face.lua:6: implicit\{\}: implicit: the ymin face is 'friction'; the implicit integrator takes free, slip, fixed and velocity faces
-- case: choices | a friction face under the implicit integrator (it holds components, it does not slide them)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "linear", boundary = { bottom = { "friction", mu = 0.3 } } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.6, 0.6} }, { material = mpm.material.hencky{ density = 1, E = 1e3 } })
local imp = sim:implicit{ dt = 0.01 }
