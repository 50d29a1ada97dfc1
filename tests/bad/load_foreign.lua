-- expect: load_foreign.lua:6: load\(\): '.*notes.h5': not an HDF5 file, so not a moraine checkpoint
-- case: files | a text file given as a checkpoint
local path = mpm.outdir .. "/notes.h5"
local f = assert(io.open(path, "w"))
f:write("these are notes, not a checkpoint\n") f:close()
local sim = mpm.load(path)
