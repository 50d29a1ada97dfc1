-- Stability of a vertical cut in undrained clay: a cut of height H in
-- ground of cohesion c and unit weight gamma = rho g stands when the
-- stability number N = gamma H / c is below the critical value and
-- collapses above it. Limit analysis brackets the critical N for a
-- frictionless (Tresca) soil in plane strain between 2.83 (lower bound) and
-- 3.83 (upper bound) (Chen, Limit Analysis and Soil Plasticity, 1975); von
-- Mises with yield sqrt(3) c is that soil in plane strain.
-- The ground is built with moraine.geometry (a slope of 90 degrees on a
-- foundation layer, and the grid around it); its initial stress is
-- lithostatic (K0 = nu / (1 - nu)) under each ground level; Cundall damping
-- D = 0.2 (000, Eqs. 61-62) makes the run quasi-static. The crest edge's
-- settlement and the largest displacement are printed (and written to
-- out/.../settlement.csv).
--
--   moraine examples/vertical_cut/deck.lua -o out/cut --set N=2.5   # stands
--   moraine examples/vertical_cut/deck.lua -o out/cut --set N=5     # collapses
--
-- Parameters: N (stability number; 3), H (m; 1), cell (m; H / 10), time (s; 1.5), quick (false).
local geometry = require "moraine.geometry"
local quick = mpm.param("quick", false)
local N = mpm.param("N", 3.0)
local H = mpm.param("H", 1.0)
local h = mpm.param("cell", H / 10)
local rho, g, E, nu = 2000, 9.81, 20e6, 0.3
local c = rho * g * H / N
local clay = mpm.material.von_mises{ density = rho, E = E, nu = nu, yield = math.sqrt(3) * c, name = "clay" }

-- H of foundation, 2 H in front of the cut, 3 H behind it
local ground, key = geometry.slope{ height = H, angle = 90, toe = 2 * H, crest = 3 * H, base = H }
local sim = mpm.simulation{
  dim = 2,
  grid = geometry.grid_around{ region_min = { 0, 0 }, region_max = { key.width, key.height }, cell = h,
                               pad = { 0, 0, 0, 2 } },
  shape = "quadratic_bspline",
  scheme = { transfer = "FLIP", stress_update = "USF" },
  gravity = { 0, -g },
  boundary = { left = "slip", right = "slip", bottom = "fixed", top = "free" },
  dt = { cfl = 0.5 },
  damping = { cundall = 0.2 },
  thermo = quick and 0 or 1000,
  output = quick and false or { vtk = "cut", every = 0.05, fields = { "displacement", "eps_D", "stress" } },
}
local K0 = nu / (1 - nu)
local xc = key.crest[1]
-- behind the cut the ground surface is at base + H, in front at base
sim:add_particles(mpm.intersection(ground, mpm.box{ min = { xc, 0 }, max = { key.width, key.height } }),
                  { material = clay, per_axis = 2, stress = mpm.lithostatic{ density = rho, top = key.height, K0 = K0 } })
sim:add_particles(mpm.intersection(ground, mpm.box{ min = { 0, 0 }, max = { xc, key.toe[2] } }),
                  { material = clay, per_axis = 2, stress = mpm.lithostatic{ density = rho, top = key.toe[2], K0 = K0 } })

-- the point at the crest edge
local edge, best = 1, math.huge
for i = 1, sim:particle_count() do
  local x = sim:particle(i).x
  local d = (x[1] - xc) ^ 2 + (x[2] - key.height) ^ 2
  if d < best then edge, best = i, d end
end
local y0 = sim:particle(edge).x[2]
os.execute("mkdir -p '" .. mpm.outdir .. "'")
local csv = assert(io.open(mpm.outdir .. "/settlement.csv", "w"))
csv:write("time,crest_settlement,max_displacement\n")
local function largest_displacement(s)
  local u, worst = s:field("displacement"), 0
  for i = 0, s:particle_count() - 1 do worst = math.max(worst, math.sqrt(u[3 * i + 1] ^ 2 + u[3 * i + 2] ^ 2)) end
  return worst
end
sim:hook{ every_time = 0.05, fn = function(s)
  csv:write(string.format("%.4g,%.6g,%.6g\n", s:time(), y0 - s:particle(edge).x[2], largest_displacement(s)))
end }
sim:run{ time = mpm.param("time", 1.5) }
csv:close()
local settlement = y0 - sim:particle(edge).x[2]
local umax = largest_displacement(sim)
print(string.format("vertical cut: N = gamma H / c = %.3g (c = %.4g kPa, H = %g m): crest settlement %.4g m (%.3g H), " ..
                    "largest displacement %.4g m: %s", N, c / 1e3, H, settlement, settlement / H, umax,
                    umax > 0.1 * H and "collapsed" or "stands"))
return { N = N, H = H, settlement = settlement, largest_displacement = umax }
