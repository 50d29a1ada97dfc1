-- The granular column collapse of 000 §5 (Camargue sand, FLIP, the
-- settle-then-collapse workflow of lua/moraine/collapse.lua) with the
-- collapse material Mohr-Coulomb (000 Table 2, the reference), mu(I) and
-- Modified Cam-Clay, the same settled column for all three.
--  - mu(I): mu_s = tan(phi) of Table 2, mu_2 = mu_s + 0.26 (the spread of
--    Jop et al.'s glass beads), I0 = 0.279, d = 0.3 mm, rho_s = 2650; the
--    elastic constants of Table 2. Its friction is never below Mohr-Coulomb's
--    (psi = 0, no cohesion), so its runout must not exceed Mohr-Coulomb's.
--  - Cam-Clay: M = 6 sin(phi) / (3 - sin(phi)) (the same critical-state
--    friction in triaxial compression), lambda = 0.05, kappa = 0.01,
--    v0 = 1.6, p_c0 = 50 kPa (over-consolidated above mid-height), nu of
--    Table 2.
-- Asserted: each collapse comes to rest inside the box; mu(I)'s runout not
-- above Mohr-Coulomb's (one cell of slack). The runouts L~ and times to rest
-- are reported with Lube et al.'s law. Quick: AR = 2, cells of 0.1 m
-- (~8 s of CPU); --set full=true: cells of 0.05 m (~50 s, label long).
-- Measured, L~ by the furthest particle (by 95 % of the mass), quick / full:
-- Mohr-Coulomb 4.80 (3.00) / 4.95 (3.00), mu(I) 3.70 (2.30) / 3.95 (2.25),
-- Cam-Clay 2.50 (1.50) / 2.60 (1.65); Lube et al. 2.71. At rest after
-- 1.72 / 1.68, 1.59 / 1.55 and 1.46 / 1.41 s.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local collapse = require "moraine.collapse"
local full = mpm.param("full", false)
local ar = mpm.param("aspect_ratio", 2)
local cell = full and 0.05 or 0.1
local t2 = collapse.table2
local deg = math.pi / 180
local mu_s = math.tan(t2.phi * deg)
local sin_phi = math.sin(t2.phi * deg)

local materials = {
  { "mohr_coulomb", false },
  { "mu_i", mpm.material.mu_i{ name = "mu_i", density = t2.density, E = t2.E, nu = t2.nu, mu_s = mu_s,
                               mu_2 = mu_s + 0.26, I0 = 0.279, d = 0.3e-3, rho_s = 2650 } },
  { "cam_clay", mpm.material.cam_clay{ name = "cam_clay", density = t2.density, M = 6 * sin_phi / (3 - sin_phi),
                                       lambda = 0.05, kappa = 0.01, nu = t2.nu, v0 = 1.6, p_c0 = mpm.param("p_c0", 5e3) } },
}

local settled, runs = nil, {}
for _, m in ipairs(materials) do
  local r = collapse.run{ aspect_ratio = ar, cell = cell, strategy = "FLIP", material = m[2] or nil,
                          settled = settled, collapse_time = 2.0 * math.sqrt(ar), name = m[1], csv = false,
                          diagnostics = false }
  settled = settled or (m[1] .. "_settled.h5")
  runs[m[1]] = r
  print(string.format("granular collapse AR = %g, %s: L~ = %.3f (95 %% of the mass %.3f), t_rest = %s s, " ..
                      "W_MPM / dEp = %.2f %%", ar, m[1], r.runout, r.runout_mass,
                      r.t_rest and string.format("%.2f", r.t_rest) or "not at rest", 100 * r.W_MPM_ratio))
  T.check(not r.at_wall, "%s: the front reached the right wall", m[1])
  T.check(r.t_rest ~= nil, "%s: not at rest after %.2f s", m[1], r.time)
  T.expect{ id = "granular_collapse." .. m[1] .. ".runout", what = m[1] .. ": normalised runout L~", value = r.runout }
end
local lube = collapse.lube(ar)
print(string.format("granular collapse AR = %g: Lube et al. L~ = %.3f", ar, lube.runout))
local mc, mi = runs.mohr_coulomb, runs.mu_i
T.check(mi.runout <= mc.runout + cell / mc.L_x_init,
        "mu(I) ran further (L~ %.3f) than Mohr-Coulomb (%.3f) although its friction is never lower", mi.runout,
        mc.runout)
T.done("granular_collapse")
