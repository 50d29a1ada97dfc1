-- The elastic cantilever of 001 §7.1 (analysis A) with the explicit step,
-- beside tests/decks/implicit_cantilever.lua (issue: the same run both ways,
-- wall time and energy drift; doc/implicit.md). Same beam, grid, uGIMP shape
-- functions, clamp and load: 500 kN split between the two end points on
-- the beam axis (sim:point_force), ramped to t = 25 s by the load factor
-- (set before each step at its mid-point time) and removed. Explicit:
-- FLIP, USF, particle CFL time step (Courant 0.5; dt is about 0.02 s).
-- Reports the wall time, the total energy change after the release (relative
-- to the energy at release, over 100 s) and the free-vibration period; asserts
-- the period against the first cantilever mode within 5 % (as the implicit
-- deck does) and that the energy put in by the load (W_ext) is what the beam
-- holds at the release, |E_k + E_el - W_ext| = |W_MPM| within 1 % of W_ext.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local E, nu, rho, P, t1 = 1e9, 0.2, 7750e3, 500e3, 25.0
local L, H = 10.0, 1.0
local tend = mpm.param("time", 125.0)
local courant = mpm.param("courant", 0.5)
local mat = mpm.material.hencky{ density = rho, E = E, nu = nu }
local sim = mpm.simulation{ dim = 2, grid = { origin = { -1, 0 }, size = { 12, 20 }, cell = 0.5 }, shape = "gimp",
                            scheme = { transfer = "FLIP", stress_update = "USF" },
                            dt = { cfl = courant }, gravity = { 0, 0 },
                            thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = { 0, 9.5 }, max = { L, 9.5 + H } }, { material = mat, per_cell = 64, placement = "regular" })
sim:constrain{ region = mpm.box{ min = { -1.01, -1 }, max = { 0.01, 21 } }, vx = 0, vy = 0 }
local n = sim:point_force{ region = mpm.box{ min = { L - 0.05, 10 - 0.05 }, max = { L, 10 + 0.05 } }, force = { 0, -P } }
T.check(n == 2, "the end load should act on 2 points, got %d", n)

local tip = T.nearest(sim, { L, 10 }) -- the end point on the beam axis
local yrest = sim:particle(tip).x[2]
local Ep = E / (1 - nu * nu)
local f1 = 1.8751 ^ 2 / (2 * math.pi) * math.sqrt(Ep * H ^ 3 / 12 / (rho * H * L ^ 4))

local function load_at(t) return t < t1 and t / t1 or 0 end
local released, eref, drift, at_release = false, nil, 0, nil
local ycross, prev_t, prev_y, steps = {}, nil, nil, 0
local t0 = mpm.wall_time()
sim:load_factor(load_at(0.5 * courant * sim:dt_estimate().cfl))
sim:hook{ every_steps = 1, fn = function(s)
  local t = s:time()
  steps = steps + 1
  s:load_factor(load_at(t + 0.5 * s:dt())) -- mid-point of the next step (its dt is close to this one's)
  local e = s:energy()
  local etot = e.kinetic + e.elastic
  if t > t1 then
    if not released then released, eref, at_release = true, etot, e end
    drift = math.max(drift, math.abs(etot - eref) / eref)
    local y = s:particle(tip).x[2] - yrest
    if prev_y and prev_y * y < 0 then ycross[#ycross + 1] = prev_t + (t - prev_t) * prev_y / (prev_y - y) end
    prev_t, prev_y = t, y
  end
end }
sim:run{ time = tend }
local wall = mpm.wall_time() - t0
local period
if #ycross >= 3 then period = 2 * (ycross[#ycross] - ycross[1]) / (#ycross - 1) end
print(string.format("explicit cantilever: %d steps, wall %.2f s, energy at release %.6g J/m (W_ext %.6g, W_MPM %.3g), "
                    .. "drift after release %.3e, period %s s vs %.4f s", steps, wall, eref or 0,
                    at_release and at_release.external or 0, at_release and at_release.mpm_error or 0, drift,
                    period and string.format("%.4f", period) or "n/a", 1 / f1))
T.check(released, "the run ended before the release")
T.expect{ id = "explicit_cantilever.energy", what = "explicit cantilever: total energy change after release (relative)",
          value = drift }
T.expect{ id = "explicit_cantilever.load_work", what = "explicit cantilever: |W_MPM| / W_ext at the release",
          value = 100 * math.abs(at_release.mpm_error) / at_release.external, max = 1, unit = "%" }
T.check(period ~= nil, "fewer than 3 zero crossings of the tip deflection")
T.expect{ id = "explicit_cantilever.period", what = "explicit cantilever: free-vibration period vs first mode",
          value = period, reference = 1 / f1, rtol = 0.05, unit = "s" }
T.done("explicit_cantilever")
