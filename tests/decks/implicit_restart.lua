-- Restart of an implicit run from a checkpoint (src/implicit/point_state.c):
-- the elasto-plastic colliding cylinders of 001 §7.3 with linear hardening
-- (so that b_e, tau, psi and xi all carry history), fixed dt, FLIP. The
-- straight run saves a checkpoint after `half` steps and goes on to `steps`;
-- a simulation loaded from the checkpoint with a new integrator of the same
-- options makes the remaining steps.
--   the loaded simulation's implicit_be is the one saved;
--   after the remaining steps its particles (displacement, v, F, stress,
--     elastic energy) and its integrator's history fields are bit for bit
--     those of the straight run, and so are the stored energy and the
--     accumulated dissipation;
--   the same after imp:free() and a new integrator on the same simulation;
--   the history matters: some point hardened (xi > 0) and the plastic
--     points' b_e is far from the F F^T a fresh start would assume (> 1e-3;
--     0.41 measured).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local steps, half = mpm.param("steps", 16), mpm.param("half", 8)
local opts = { dt = 0.25, mapping = "FLIP", min_node_mass = 1e-3 }
local mat = mpm.material.von_mises{ density = 5, E = 100, nu = 0.3, yield = math.sqrt(1.5) * 10, hardening = 20 }

local colliding_cylinders = dofile(mpm.deck_dir .. "/colliding_cylinders.lua")
local function cylinders() return colliding_cylinders(mat) end
local sim = cylinders()
local imp = sim:implicit(opts)
for _ = 1, half do imp:step() end
local path = sim:save("implicit_restart.h5")
local saved_be = sim:field("implicit_be")
for _ = half + 1, steps do imp:step() end
local e_straight = imp:energy()

-- how far the plastic points' b_e is from F F^T: what a fresh start would lose
local F, be = sim:field("deformation_gradient"), sim:field("implicit_be")
local off_fresh = 0
for i = 1, sim:particle_count() do
  local f = function(a, b) return F[(i - 1) * 9 + 3 * (a - 1) + b] end
  for a = 1, 3 do
    for c = 1, 3 do
      local ffT = f(a, 1) * f(c, 1) + f(a, 2) * f(c, 2) + f(a, 3) * f(c, 3)
      off_fresh = math.max(off_fresh, math.abs(be[(i - 1) * 9 + 3 * (a - 1) + c] - ffT))
    end
  end
end

local loaded = mpm.load(path, { thermo = 0, diagnostics = false })
local loaded_be = loaded:field("implicit_be")
local same_saved = #loaded_be == #saved_be
for k = 1, #saved_be do same_saved = same_saved and loaded_be[k] == saved_be[k] end
local imp2 = loaded:implicit(opts)
for _ = half + 1, steps do imp2:step() end
local e_loaded = imp2:energy()

-- a new integrator on the same simulation after imp:free() continues the same way
local again = cylinders()
local first = again:implicit(opts)
for _ = 1, half do first:step() end
first:free()
local second = again:implicit(opts)
for _ = half + 1, steps do second:step() end

local function difference(other)
  local worst = 0
  for _, name in ipairs{ "displacement", "velocity", "deformation_gradient", "stress", "implicit_be", "implicit_tau",
                         "implicit_psi", "implicit_xi", "elastic_energy" } do
    local a, b = sim:field(name), other:field(name)
    T.check(#a == #b, "%s: %d values in the straight run, %d in the other", name, #a, #b)
    for k = 1, #a do worst = math.max(worst, math.abs(a[k] - b[k])) end
  end
  return worst
end
local worst, worst_again = difference(loaded), difference(again)
local xi = sim:field("implicit_xi")
local xmax = 0
for k = 1, #xi do xmax = math.max(xmax, xi[k]) end
print(string.format("implicit restart after %d of %d steps: largest difference %.3g (after imp:free() and a new "
                    .. "integrator %.3g); dissipated %.6g (straight) "
                    .. "%.6g (restarted) J/m; largest xi %.4g; largest |b_e - F F^T| %.3g", half, steps, worst,
                    worst_again, e_straight.dissipated, e_loaded.dissipated, xmax, off_fresh))
T.check(same_saved, "the loaded implicit_be differs from the saved one")
T.check(xmax > 0, "no point hardened: the test does not exercise the plastic history")
T.check(off_fresh > 1e-3, "b_e stays F F^T (%g): the test does not exercise the plastic history", off_fresh)
T.expect{ id = "implicit_restart.difference", what = "largest difference of the particle fields, restarted vs straight",
          value = worst, max = 0 }
T.expect{ id = "implicit_restart.again", what = "largest difference, new integrator after imp:free() vs straight",
          value = worst_again, max = 0 }
T.expect{ id = "implicit_restart.dissipation", what = "accumulated dissipation, restarted vs straight (J/m)",
          value = e_loaded.dissipated, reference = e_straight.dissipated, rtol = 0 }
T.expect{ id = "implicit_restart.strain", what = "stored energy, restarted vs straight (J/m)", value = e_loaded.strain,
          reference = e_straight.strain, rtol = 0 }
T.done("implicit_restart")
