-- Elastic cantilever, implicit energy-momentum consistent MPM (001 §7.1,
-- analysis A): a 10 m x 1 m Hencky beam (E = 1e9 Pa, nu = 0.2,
-- rho = 7750e3 kg/m^3 as in 001 Table 3), clamped at x = 0 by fixing the grid
-- nodes there, on a grid of 0.5 m cells with uGIMP shape functions. A point
-- load split between the two end points next to the beam axis rises to
-- 500 kN at t = 25 s and is then removed. Consistent mass, FLIP, tol 1e-11,
-- fixed dt = 0.6264 s (001 Table 3), run to 125 s (100 s after the release).
-- After the release the total energy (kinetic + strain) must stay constant to
-- 1e-6 relative, and the free-vibration period (tip displacement crossings)
-- must match the first cantilever mode, f1 = 1.8751^2 / (2 pi) sqrt(E' I / (rho A L^4)),
-- E' = E / (1 - nu^2) in plane strain, within 5 %.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local E, nu, rho, P, t1 = 1e9, 0.2, 7750e3, 500e3, 25.0
local L, H = 10.0, 1.0
local tend = mpm.param("time", 125.0) -- 100 s after the release
local mat = mpm.material.hencky{ density = rho, E = E, nu = nu }
local sim = mpm.simulation{ dim = 2, grid = { origin = { -1, 0 }, size = { 12, 20 }, cell = 0.5 }, shape = mpm.param("shape", "gimp"),
                            thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = { 0, 9.5 }, max = { L, 9.5 + H } },
                  { material = mat, per_cell = mpm.param("per_cell", 64), placement = "regular" })
sim:constrain{ region = mpm.box{ min = { -1.01, -1 }, max = { 0.01, 21 } }, vx = 0, vy = 0 }
local load_region = mpm.box{ min = { L - 0.05, 10 - 0.05 }, max = { L, 10 + 0.05 } }

local tip = T.nearest(sim, { L, 10 }) -- the end point on the beam axis, for the tip deflection
local function load_at(t) return t < t1 and P * t / t1 or 0 end

-- first bending mode of the clamped beam (Euler-Bernoulli, plane strain)
local Ep = E / (1 - nu * nu)
local f1 = 1.8751 ^ 2 / (2 * math.pi) * math.sqrt(Ep * H ^ 3 / 12 / (rho * H * L ^ 4))

local t0 = mpm.wall_time()
local released, eref, drift = false, nil, 0
local ycross, prev_t, prev_y, yrest = {}, nil, nil, sim:particle(tip).x[2]
local iters, worst_final, worst_rate, steps, over6 = 0, 0, 0, 0, 0
local imp = sim:implicit{ mass = "consistent", mapping = "FLIP", tol = 1e-11, dt = mpm.param("dt", 0.6264),
                      min_node_mass = mpm.param("min_node_mass", 1e-3) }
local n = imp:point_force{ region = load_region, force = { 0, -P } }
T.check(n == 2, "the end load should act on 2 points, got %d", n)
local function step_once()
  local t = sim:time()
  local dt = imp:next_dt()
  imp:load_factor(load_at(t + 0.5 * dt) / P) -- mid-point load (001 Eq. 20 at t + dt/2)
  local h = imp:step()
  iters = math.max(iters, h.iterations)
  if h.iterations > 6 then over6 = over6 + 1 end
  local k = h.iterations
  if k >= 1 and h.errors[k] > 0 then
    worst_final = math.max(worst_final, h.errors[k])
    if k >= 3 then worst_rate = math.max(worst_rate, h.errors[k] / h.errors[k - 1]) end
  end
  local e = imp:energy()
  return e.kinetic + e.strain, t + dt
end
while sim:time() < tend - 1e-9 do
  local etot, tnow = step_once()
  steps = steps + 1
  if tnow > t1 then
    if not released then released, eref = true, etot end
    drift = math.max(drift, math.abs(etot - eref) / eref)
    local y = sim:particle(tip).x[2] - yrest
    if prev_y and prev_y * y < 0 then
      ycross[#ycross + 1] = prev_t + (tnow - prev_t) * prev_y / (prev_y - y)
    end
    prev_t, prev_y = tnow, y
  end
end
local wall = mpm.wall_time() - t0
local period
if #ycross >= 3 then period = 2 * (ycross[#ycross] - ycross[1]) / (#ycross - 1) end
print(string.format("cantilever: %d steps, wall %.2f s, energy after release %.6g J/m, drift %.3e, "
                    .. "Newton <= %d iterations (%d steps > 6; final ratio <= %.2e, last reduction <= %.2e), period %s s vs %.4f s (f1 = %.5f Hz)",
                    steps, wall, eref or 0, drift, iters, over6, worst_final, worst_rate,
                    period and string.format("%.4f", period) or "n/a", 1 / f1, f1))
T.expect{ id = "implicit_cantilever.energy", what = "cantilever: total energy change after release (relative)",
          value = drift, max = 1e-6 }
T.expect{ id = "implicit_cantilever.newton_iterations", what = "cantilever: most Newton iterations", value = iters, max = 6 }
T.expect{ id = "implicit_cantilever.newton_rate", what = "cantilever: largest last-iteration error reduction",
          value = worst_rate, max = 1e-2 }
T.expect{ id = "implicit_cantilever.newton_final", what = "cantilever: largest final f_err ratio", value = worst_final, max = 1e-10 }
T.check(period ~= nil, "fewer than 3 zero crossings of the tip deflection")
T.expect{ id = "implicit_cantilever.period", what = "cantilever: free-vibration period vs first mode",
          value = period, reference = 1 / f1, rtol = 0.05, unit = "s" }
T.done("implicit_cantilever")
