-- Plane Poiseuille start-up flow (004 §3.1): a viscous fluid at rest between
-- two no-slip plates 5 mm apart, periodic along the channel, is driven by a
-- body force from t = 0. The velocity profile develops towards the parabola;
-- the deck writes it at three times next to the series solution of Morris,
-- Fox & Zhu (1997). See README.md.
--
--   moraine examples/poiseuille/deck.lua -o out/poiseuille
--   moraine examples/poiseuille/deck.lua -o out/poiseuille --set cells=64 --set transfer=FLIP0.99
--
-- Parameters: cells (cells across the channel; 32), transfer (APIC), boundary
-- (shape_boundary: wls), quick (false).
local quick = mpm.param("quick", false)
local H, F, rho, mu, K = 5e-3, 10.0, 1000.0, 0.5, 1.4e5 -- 004's data in SI
local nu = mu / rho
local Tdiff = H * H / nu -- 0.05 s
local N = math.tointeger(mpm.param("cells", quick and 8 or 32))
local h = H / N
local fractions = quick and { 0.05 } or { 0.05, 0.15, 0.5 }

local analytic = require "moraine.analytic"
local function series(y, t) return analytic.poiseuille(y, t, { H = H, nu = nu, F = F }) end

local fluid = mpm.material.newtonian{ density = rho, viscosity = mu, sound_speed = math.sqrt(K / rho) }
local sim = mpm.simulation{
  dim = 2,
  grid = { size = { 4 * h, H }, cell = h }, -- a slab 4 cells long: the flow does not vary along x
  shape = "quadratic_bspline",
  shape_boundary = mpm.param("boundary", "wls"),
  scheme = { transfer = mpm.param("transfer", "APIC"), stress_update = "USF" },
  gravity = { F, 0 },
  boundary = { left = "periodic", right = "periodic", bottom = "fixed", top = "fixed" },
  dt = { cfl = 0.5 },
  thermo = 0,
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 4 * h, H } }, { material = fluid, per_axis = 2 })

os.execute("mkdir -p '" .. mpm.outdir .. "'")
for _, frac in ipairs(fractions) do
  local csv = assert(io.open(string.format("%s/profile_t%.2f.csv", mpm.outdir, frac), "w"))
  csv:write("y,u_mpm,u_series\n")
  local t = frac * Tdiff
  sim:run{ time = t - sim:time() }
  -- particles sit in layers of equal y (2 per cell); average u over each layer
  local sum, count = {}, {}
  for i = 1, sim:particle_count() do
    local p = sim:particle(i)
    local layer = math.floor(p.x[2] / (h / 2))
    sum[layer] = (sum[layer] or 0) + p.v[1]
    count[layer] = (count[layer] or 0) + 1
  end
  local worst, ymid, umid = 0, 0, 0
  local uc = series(H / 2, t)
  for layer = 0, 2 * N - 1 do
    if count[layer] then
      local y = (math.floor(layer / 2) + (layer % 2 == 0 and 0.5 - 0.5 / math.sqrt(3) or 0.5 + 0.5 / math.sqrt(3))) * h
      local u = sum[layer] / count[layer]
      csv:write(string.format("%.9g,%.9g,%.9g\n", y, u, series(y, t)))
      worst = math.max(worst, math.abs(u - series(y, t)) / uc)
      if layer == N then ymid, umid = y, u end
    end
  end
  csv:close()
  print(string.format("poiseuille: t/T = %.2f, u = %.5f m/s at y/H = %.3f (series %.5f); largest layer error %.3f %% of the centreline speed",
                      frac, umid, ymid / H, series(ymid, t), 100 * worst))
end
