-- expect: wall_mesh_2d\.lua:5: add_wall\{\}: shape: a mesh wall is 3D only
-- case: choices | a mesh wall in a 2D simulation
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 } }
sim:add_wall{ name = "rock", shape = "mesh", file = "rock.stl" }
