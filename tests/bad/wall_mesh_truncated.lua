-- expect: wall_mesh_truncated\.lua:11: add_wall\{\}: '.*cut\.stl': truncated or corrupted binary STL: its header counts 12 triangles, 684 bytes, the file has 400
-- case: files | a mesh wall from a truncated binary STL file
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 1 }, cell = 0.1 } }
-- the header of 12 triangles, then 400 - 84 bytes of them: the file was cut
local parts = { string.pack("<c80I4", "cut", 12) }
for i = 1, 8 do parts[#parts + 1] = string.pack("<fff fff fff fff I2", 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0) end
local f = assert(io.open(mpm.outdir .. "/cut.stl", "wb"))
f:write(table.concat(parts):sub(1, 400))
f:close()
sim:add_wall{ name = "rock", shape = "mesh", file = mpm.outdir .. "/cut.stl" }
