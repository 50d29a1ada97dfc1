-- expect: wall_mesh_missing\.lua:5: add_wall\{\}: 'no_such_mesh\.stl': cannot open: No such file or directory
-- case: files | a mesh wall whose STL file does not exist
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 1 }, cell = 0.1 } }
sim:add_wall{ name = "rock", shape = "mesh", file = "no_such_mesh.stl" }
