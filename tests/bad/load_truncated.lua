-- expect: load_truncated.lua:11: load\(\): '.*cut.h5': truncated or corrupted HDF5 file
-- case: files | a truncated checkpoint
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.05 }, thermo = 0, diagnostics = false }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.8, 0.8 } }, { material = mat })
local whole = sim:save("whole.h5")
local f = assert(io.open(whole, "rb")) local bytes = f:read("a") f:close()
local cut = mpm.outdir .. "/cut.h5"
f = assert(io.open(cut, "wb")) f:write(bytes:sub(1, #bytes // 2)) f:close()
-- a truncated copy is refused
local again = mpm.load(cut)
