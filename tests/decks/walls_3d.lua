-- Rigid walls in 3D: an elastic block (0.4 m x 0.2 m x 0.2 m, E = 1 MPa,
-- nu = 0.3, rho = 1000 kg/m^3, 2 x 2 x 2 points per 0.05 m cell, quadratic
-- B-splines) on a friction plane tilted by theta about y, gravity vertical:
--   slide (35 deg, mu = 0.3, 0.6 s): a along the plane from the centre of mass
--         against g (sin theta - mu cos theta) within 3 %;
--   stick (25 deg, mu = 0.8, 0.4 s): creep below 1 % of the frictionless
--         distance.
--   --set strategies=FLIP,APIC,...
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local strategies = {}
for item in mpm.param("strategies", "FLIP,APIC"):gmatch("[^,%s]+") do strategies[#strategies + 1] = item end
local g, rho, E, cell = 9.81, 1000, 1e6, 0.05

-- the distance the block moved down the plane
local function run(strategy, theta, mu, time)
  local th = math.rad(theta)
  local n, t, p = { math.sin(th), 0, math.cos(th) }, { math.cos(th), 0, -math.sin(th) }, { 0.1, 0, 1.3 }
  local sim = mpm.simulation{ dim = 3, grid = { size = { 2.0, 0.5, 1.6 }, cell = cell }, shape = "quadratic_bspline",
                              scheme = strategy, gravity = { 0, 0, -g }, boundary = { all = "slip", top = "free" },
                              dt = { a_tau = 0.2 }, diagnostics = false, thermo = 0, progress = false }
  sim:add_wall{ name = "incline", shape = "plane", point = p, normal = n, kind = "friction", mu = mu }
  local block = mpm.region(function(x, y, z)
    local s, h = (x - p[1]) * t[1] + (z - p[3]) * t[3], (x - p[1]) * n[1] + (z - p[3]) * n[3]
    return s > 0.2 and s < 0.6 and h > 0 and h < 0.2 and y > 0.15 and y < 0.35
  end)
  sim:add_particles(mpm.box{ min = { 0, 0.15, 0.6 }, max = { 1.0, 0.35, 1.5 } } * block,
                    { material = mpm.material.linear_elastic{ density = rho, E = E, nu = 0.3 }, per_cell = 8 })
  local c0 = sim:diagnostics().center_of_mass
  sim:run{ time = time }
  local c = sim:diagnostics().center_of_mass
  return (c[1] - c0[1]) * t[1] + (c[3] - c0[3]) * t[3]
end

local worst = { slide = 0, creep = 0 }
for _, strategy in ipairs(strategies) do
  local s = run(strategy, 35, 0.3, 0.6)
  local a, exact = 2 * s / 0.36, g * (math.sin(math.rad(35)) - 0.3 * math.cos(math.rad(35)))
  worst.slide = math.max(worst.slide, math.abs(a / exact - 1))
  T.check(math.abs(a / exact - 1) <= 0.03, "3D %s: a = %.4f m/s^2, closed form %.4f", strategy, a, exact)
  s = run(strategy, 25, 0.8, 0.4)
  local free = 0.5 * g * math.sin(math.rad(25)) * 0.16
  worst.creep = math.max(worst.creep, math.abs(s) / free)
  T.check(math.abs(s) < 0.01 * free, "3D %s: the block should stick, but crept %.3g m (frictionless %.3g m)", strategy,
          s, free)
end
T.expect{ id = "walls.3d.slide", what = "3D: worst |a / a_exact - 1| on an inclined plane", value = 100 * worst.slide,
          max = 3, unit = "%" }
T.expect{ id = "walls.3d.creep", what = "3D: worst creep of a sticking block", value = 100 * worst.creep, max = 1,
          unit = "% of frictionless" }
T.done("walls_3d")
