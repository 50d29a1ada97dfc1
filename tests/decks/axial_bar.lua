-- Axial vibration of a fixed-free elastic bar (VALIDATION: L = 25, E = 100,
-- rho = 1, v0 = 0.1 sin(pi x / 2L), T1 = 4 L / c = 10 s, v_cm(0) = 0.063662,
-- E_tot = 0.0625; 16 cells along the bar, 2 particles per cell, FLIP).
-- Run in 2D with nu = 0 and slip walls above and below, so the bar is
-- one-dimensional and the plane-strain modulus equals E. The period measured
-- from the zero crossings of the centre-of-mass velocity is within 2 % of
-- 4 L / c, and v_cm(0) within 2.5 % of 0.063662, with linear shape functions
-- on 16 cells (the classic case) and with quadratic B-splines on 32 cells.
-- (Quadratic B-splines on 16 cells give 2.7 %: their error near the fixed end
-- is first order in h with the ghost-node boundary; see doc/validation.md.)
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local L, E, rho = 25.0, 100.0, 1.0
local cells = mpm.param("cells", 16)
local h = L / cells
local c = math.sqrt(E / rho)
local mat = mpm.material.linear_elastic{ density = rho, E = E, nu = 0 }
local sim = mpm.simulation{
  dim = 2, grid = { size = { 2 * L, h }, cell = h }, gravity = { 0, 0 }, shape = mpm.param("shape", "linear"),
  scheme = { transfer = mpm.param("transfer", "FLIP"), stress_update = mpm.param("stress_update", "USF"),
             volumetric = mpm.param("volumetric", "standard") },
  dt = { fixed = 0.1 * h / c },
  boundary = { left = "fixed", right = "free", bottom = "slip", top = "slip" },
  thermo = 0, diagnostics = "bar.csv",
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L, h } }, {
  material = mat, per_axis = 2,
  velocity = function(x, y, z) return 0.1 * math.sin(math.pi * x / (2 * L)), 0 end,
})
local v0 = sim:diagnostics().com_velocity[1]
local label = string.format("axial_bar.%s_%d", mpm.param("shape", "linear"), cells)
T.expect{ id = label .. ".v0", what = "v_cm(0)", value = v0, reference = 0.063662, rtol = 0.025, unit = "m/s" }

-- zero crossings of v_cm by linear interpolation between steps
local crossings, prev_v, prev_t = {}, v0, 0
sim:hook{ every_steps = 1, fn = function(s)
  local v, t = s:diagnostics().com_velocity[1], s:time()
  if prev_v > 0 and v <= 0 or prev_v < 0 and v >= 0 then
    crossings[#crossings + 1] = prev_t + (t - prev_t) * prev_v / (prev_v - v)
  end
  prev_v, prev_t = v, t
end }
sim:run{ time = 2.2 * 4 * L / c }
T.check(#crossings >= 4, "expected at least 4 zero crossings of v_cm, got %d", #crossings)
-- crossings are half a period apart; average over the run
local period = 2 * (crossings[#crossings] - crossings[1]) / (#crossings - 1)
-- quadratic B-splines on 16 cells miss the 2 % (see the header): reported, not asserted
local err = T.expect{ id = label .. ".period", what = "period from the zero crossings of v_cm", value = period,
                      reference = 4 * L / c, rtol = 0.02, unit = "s",
                      asserted = mpm.param("assert_period", true) }
local e = sim:energy()
print(string.format("axial bar: period %.4f s (expected %.4f, error %.2f %%), v_cm(0) = %.6f, E_total = %.6f (initial 0.0625)",
                    period, 4 * L / c, 100 * err, v0, e.total))
T.done("axial_bar")
