-- Settling of an elastic column under gravity (000 §5.2 and Fig. 13):
--  - FLIP with Cundall damping D = 0.1 (000, Eqs. 61-62) reaches the
--    lithostatic vertical stress -rho g (H - y0) within 3 % at mid-height;
--  - without damping FLIP keeps oscillating (its kinetic energy stays orders
--    of magnitude above the damped run's);
--  - the damping work is negative and the energy balance closes:
--    |W_MPM| (000, Eq. 68) stays small against the potential-energy drop.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local rho, E, nu, g, H = 1748, 12.84e6, 0.16, 9.81, 1.0
local mat = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }

local function settle(damping)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 0.4, 1.2 }, cell = 0.05 }, gravity = { 0, -g },
    scheme = { transfer = "FLIP", stress_update = "USF" }, dt = { a_tau = 0.2 }, damping = { cundall = damping },
    boundary = { left = "slip", right = "slip", bottom = "slip", top = "free" }, thermo = 0,
    diagnostics = string.format("settle_D%g.csv", damping) }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.4, H } }, { material = mat, per_axis = 2 })
  local e0 = sim:energy()
  sim:run{ time = 1.0 }
  local u = sim:field("displacement")
  local sum, ref, n = 0, 0, 0
  for i = 1, sim:particle_count() do
    local p = sim:particle(i)
    if math.abs(p.x[2] - 0.5 * H) < 0.1 then
      sum = sum + p.stress[2]
      ref = ref - rho * g * (H - (p.x[2] - u[3 * (i - 1) + 2]))
      n = n + 1
    end
  end
  local e = sim:energy()
  local drop = math.abs((e.gravity + e.elastic) - (e0.gravity + e0.elastic)) -- (000, Eq. 69)
  sim:free()
  return sum / n, ref / n, e, drop
end

local s_damped, ref, e_damped, drop = settle(0.1)
local err = T.expect{ id = "settling.sigma_yy", what = "sigma_yy at mid-height with Cundall D = 0.1 (FLIP)", value = s_damped,
                     reference = ref, rtol = 0.03, unit = "Pa" }
T.check(e_damped.damping < 0, "damping work %g should be negative", e_damped.damping)
T.expect{ id = "settling.W_MPM", what = "|W_MPM| (000, Eq. 68) against the potential-energy drop",
          value = 100 * math.abs(e_damped.mpm_error) / drop, max = 1, unit = "%" }
local _, _, e_free = settle(0)
T.check(e_free.kinetic > 100 * e_damped.kinetic, "undamped FLIP E_k %g is not well above the damped %g",
        e_free.kinetic, e_damped.kinetic)
print(string.format("settling: sigma_yy error %.2f %% (D = 0.1), E_k %.3g J/m damped vs %.3g J/m undamped, " ..
                    "W_damp = %.4g J/m, W_MPM = %.3g J/m (%.3f %% of the drop %.4g J/m)",
                    100 * err, e_damped.kinetic, e_free.kinetic, e_damped.damping, e_damped.mpm_error,
                    100 * math.abs(e_damped.mpm_error) / drop, drop))
T.done("settling")
