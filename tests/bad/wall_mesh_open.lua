-- expect: wall_mesh_open\.lua:16: add_wall\{\}: '.*open\.stl': the mesh is not closed and oriented: the edge \(1, 0, 1\)-\(1, 1, 1\) of triangle 3 borders no other triangle \(the mesh has a hole\)
-- case: geometry | a mesh wall whose STL file misses a triangle
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 1 }, cell = 0.1 } }
-- a unit cube's 12 triangles but the last
local c = function(i) return string.format("%d %d %d", i & 1, (i >> 1) & 1, (i >> 2) & 1) end
local faces = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } }
local f = assert(io.open(mpm.outdir .. "/open.stl", "w"))
f:write("solid open\n")
for i, q in ipairs(faces) do
  for h = 1, (i < 6 and 2 or 1) do
    f:write("facet normal 0 0 0\nouter loop\n", "vertex ", c(q[1]), "\nvertex ", c(q[h + 1]), "\nvertex ", c(q[h + 2]),
            "\nendloop\nendfacet\n")
  end
end
f:write("endsolid open\n") f:close() sim:add_wall{ name = "cube", shape = "mesh", file = mpm.outdir .. "/open.stl" }
