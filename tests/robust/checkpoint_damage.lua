-- moraine robustness: damaged checkpoints, for tests/robust/checkpoint_damage.sh.
-- --set file=PATH loads that checkpoint and takes a step; without it the
-- deck saves OUT/ck.h5 for the script to damage.
local mpm = require "moraine"
local file = mpm.param("file", "")
if file ~= "" then
  local sim = mpm.load(file, { diagnostics = false })
  sim:run{ steps = 1 }
  return
end
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false,
  series = false, dt = { fixed = 1e-3 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 3 }
sim:save("ck.h5")
