-- Lithostatic column (VALIDATION: sigma_v = -rho g (H - y), K0 = nu / (1 - nu)).
-- An elastic column in a slip-walled box settles under gravity; PIC damps
-- the oscillation. At mid-height sigma_yy is within 5 % of -rho g (H - y)
-- and sigma_xx / sigma_yy within 10 % of nu / (1 - nu).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local rho, E, nu, g, H = 2000, 1e7, 0.3, 9.81, 1.0
local mat = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }
local sim = mpm.simulation{
  dim = 2, grid = { size = { 0.4, 1.2 }, cell = 0.05 }, gravity = { 0, -g },
  scheme = { transfer = "PIC", stress_update = "USF" }, dt = { a_tau = 0.3 },
  boundary = { left = "slip", right = "slip", bottom = "slip", top = "free" },
  thermo = 1000, diagnostics = "lithostatic.csv",
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.4, H } }, { material = mat, per_axis = 2 })
sim:run{ time = 1.5 }

-- particles near mid-height; the load on a particle is the weight of the
-- material that was above it, rho g (H - y0) with y0 its initial height
local u = sim:field("displacement") -- 3 components per particle
local sum_yy, sum_xx, ref_sum, count = 0, 0, 0, 0
for i = 1, sim:particle_count() do
  local p = sim:particle(i)
  if math.abs(p.x[2] - 0.5 * H) < 0.1 then
    local y0 = p.x[2] - u[3 * (i - 1) + 2]
    sum_yy = sum_yy + p.stress[2]
    sum_xx = sum_xx + p.stress[1]
    ref_sum = ref_sum - rho * g * (H - y0)
    count = count + 1
  end
end
T.check(count > 10, "too few particles at mid-height (%d)", count)
local err = T.expect{ id = "lithostatic.sigma_yy", what = "mean sigma_yy at mid-height", value = sum_yy / count,
                     reference = ref_sum / count, rtol = 0.05, unit = "Pa" }
local ratio = sum_xx / sum_yy
local err_k = T.expect{ id = "lithostatic.K0", what = "sigma_xx / sigma_yy at mid-height", value = ratio,
                       reference = nu / (1 - nu), rtol = 0.10 }
local e = sim:energy()
print(string.format("lithostatic: sigma_yy error %.2f %%, K0 = %.4f (expected %.4f, error %.2f %%), E_k = %.3g J/m",
                    100 * err, ratio, nu / (1 - nu), 100 * err_k, e.kinetic))
T.done("lithostatic")
