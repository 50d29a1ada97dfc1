-- The HDF5 time series of a run and its grid snapshots: the series holds the
-- diagnostics of the CSV and a value recorded from Lua (sim:record), read back
-- with h5py and h5dump by tests/python/check_series_h5.py; the .vti files are
-- read by VTK (tests/python/check_vti.py).
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, gravity = {0,-9.81}, thermo = 0, output = { vtk = "s", every_steps = 20, grid = true } }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.6, 0.6 } }, { material = mat })
sim:hook{ every_steps = 10, fn = function(s) s:record("front", s:reduce("max", "x")) end }
sim:run{ steps = 50 }
