-- The history variables of mu_i and cam_clay survive a checkpoint: a
-- column collapsing under gravity, N steps, save, load, N more steps gives
-- the particles of 2N steps straight, bit for bit (as checkpoint_workflow.lua
-- checks for the other models).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local beads = mpm.material.mu_i{ density = 1470, E = 2e6, nu = 0.3 }
local clay = mpm.material.cam_clay{ density = 1800, M = 1.0, lambda = 0.2, kappa = 0.04, v0 = 2.0, p_c0 = 5e3,
                                    p_min = 500 }

local function column(material, name)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.6 }, cell = 0.05 }, gravity = { 0, -9.81 },
    shape = "quadratic_bspline", scheme = { transfer = "FLIP", stress_update = "USF" }, dt = { cfl = 0.4 },
    boundary = { all = "slip", top = "free" }, thermo = 0, diagnostics = false, name = name }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.2, 0.4 } }, { material = material, per_axis = 2,
    stress = mpm.lithostatic{ density = material.density, top = 0.4, K0 = 0.5 } })
  return sim
end

for _, case in ipairs{ { beads, "mu_i" }, { clay, "cam_clay" } } do
  local straight = column(case[1], case[2] .. "_straight")
  straight:run{ steps = 150 }
  local path = straight:save(case[2] .. "_150.h5")
  straight:run{ steps = 150 }
  local resumed = mpm.load(path, { diagnostics = false, thermo = 0 })
  resumed:run{ steps = 150 }
  for _, f in ipairs{ "stress", "velocity", "displacement", "deformation_gradient" } do
    local x, y = straight:field(f), resumed:field(f)
    for i = 1, #x do T.check(x[i] == y[i], "%s restart: %s[%d] differs: %.17g vs %.17g", case[2], f, i, x[i], y[i]) end
  end
  -- the column has started to collapse: plastic work was done
  T.check(straight:energy().plastic < 0, "%s: no plastic work after 300 steps", case[2])
  print(string.format("%s: restart bit for bit after %d steps; plastic work %.4g J/m", case[2], straight:step(),
                      straight:energy().plastic))
end
T.done("granular_restart")
