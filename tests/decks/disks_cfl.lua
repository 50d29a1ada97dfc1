-- Two elastic disks collide (the parameters of 001 §7.2: E = 100 Pa,
-- nu = 0.3, rho = 5 kg/m^3, radius 2 m, centres (5.8, 5.5) and (14.2, 6.5),
-- speed 0.75 m/s towards each other, a 20 m x 12 m box) with the
-- adaptive time-step policies: the particle CFL (002, Eqs. 34-37) at
-- Courant 0.5 and the grid-averaged CFL (001, Eqs. 58-61). The dt is logged
-- at every step; the run does not blow up and the total energy stays within
-- 5 % through the impact (FLIP + USF, 0.25 m cells).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 5, E = 100, nu = 0.3 }

for _, policy in ipairs{ { cfl = 0.5 }, { grid_cfl = 0.5 } } do
  local name = policy.cfl and "cfl" or "grid_cfl"
  local sim = mpm.simulation{ dim = 2, grid = { size = { 20, 12 }, cell = 0.25 }, shape = "cubic_bspline",
    scheme = { transfer = "FLIP", stress_update = "USF" }, dt = policy, boundary = { all = "slip" },
    thermo = 0, diagnostics = name .. ".csv", diagnostics_every = 1 }
  sim:add_particles(mpm.disk{ center = { 5.8, 5.5 }, radius = 2 }, { material = mat, velocity = { 0.75, 0 } })
  sim:add_particles(mpm.disk{ center = { 14.2, 6.5 }, radius = 2 }, { material = mat, velocity = { -0.75, 0 } })
  local e0 = sim:energy().total
  local worst, dts = 0, {}
  sim:hook{ every_steps = 1, fn = function(s)
    worst = math.max(worst, math.abs(s:energy().total - e0) / e0)
    dts[#dts + 1] = s:dt()
  end }
  local est = sim:dt_estimate()
  sim:run{ time = mpm.param("time", 8.0) } -- the disks meet near t = 3 s and separate
  local lo, hi = math.huge, 0
  for i = 2, #dts do lo, hi = math.min(lo, dts[i]), math.max(hi, dts[i]) end
  print(string.format("disks %-8s: %d steps, dt from %.4g to %.4g s (critical at start %.4g s), largest energy change %.2f %%",
                      name, sim:step(), lo, hi, est[name], 100 * worst))
  T.expect{ id = "disks_cfl." .. name, what = name .. ": largest total-energy change through the impact",
            value = 100 * worst, max = 5, unit = "%" }
  T.check(hi > lo, "%s: dt never changed (%g)", name, lo)
  -- every step has a row in the CSV with its dt
  local rows = 0
  for line in io.lines(mpm.outdir .. "/" .. name .. ".csv") do rows = rows + 1 end
  T.check(rows == sim:step() + 2, "%s: the CSV has %d rows for %d steps", name, rows - 1, sim:step())
  sim:free()
end
T.done("disks_cfl")
