-- expect: safe_save_outside\.lua:8: save\(\): '/tmp/moraine-safe-state\.h5' is outside the output directory '.*'; --safe allows writes only below the output directory
-- case: permission | --safe: a checkpoint saved outside the output directory
-- options: --safe
-- status: 1
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0 }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:save("/tmp/moraine-safe-state.h5")
error("a checkpoint outside the output directory was not refused")
