-- expect: import_missing\.lua:6: import\(\): '.*/missing\.h5': cannot open: No such file or directory
-- case: files | importing a checkpoint that does not exist
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:import("missing.h5")
