-- Coulomb friction on a friction face against closed forms, for every
-- motion-integration strategy (000 Table 1) and several shape functions.
--
-- An elastic block (0.4 m x 0.2 m, x 0.2 m in 3D; E = 1 MPa, nu = 0.3,
-- rho = 1000 kg/m^3; 2 points per cell along each axis) rests on a friction
-- face. Gravity is tilted by theta from the face normal, so the closed forms
-- of a rigid block on a Coulomb floor hold:
--   slide  (tan theta > mu, from rest, 0.6 s): a = g (sin theta - mu cos theta),
--          two (theta, mu) pairs: (30 deg, 0.3) and (40 deg, 0.5); a from the
--          centre of mass, x = a t^2 / 2, within 3 %;
--   stick  (theta = 10 deg, mu = 0.3 > tan theta, 0.4 s): the centre of mass
--          creeps less than 1 % of the frictionless distance g sin theta t^2 / 2;
--   stop   (theta = 0, v0 = 2 m/s, mu = 0.3): the stopping distance
--          v0^2 / (2 mu g) within 3 %, and the block at rest;
--   side   the 30 deg, mu = 0.3 slide against a side wall (xmin), gravity
--          along the wall: the same a within 3 %.
-- Reported with their targets, not asserted (doc/validation.md, "friction"):
-- over all the runs, the worst deviation of W_friction from -mu N d (target
-- 5 %) and the worst elastic energy at the end against the kinetic energy
-- (at release for the stopping block, at the end for the others; target
-- 1 %). Under the strategies that keep energy (all but PIC) a vibration of
-- the sliding block grows, fed by friction; it and the contact's impacts,
-- which dissipate it without booking, take their share of the energy: PIC
-- meets both targets (asserted for PIC), the others miss them by up to about
-- 18 % (what feeds the vibration: friction_layer.lua; doc/numerics.md,
-- "Friction faces").
--
-- FLIP/particles: FLIP with scheme holds = "particles" (the holds of V
-- reach its particles); NAME/particles the same for any strategy.
--
--   --set dim=2|3  --set strategies=PIC,FLIP,...  --set shapes=quadratic_bspline,...
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local dim = math.tointeger(mpm.param("dim", 2))
local list = T.list
local strategies = list(mpm.param("strategies", "PIC,FLIP,APIC,TPIC,AFLIP,TFLIP,XPIC(2),MLS,FLIP/particles"))
local shapes = list(mpm.param("shapes", "quadratic_bspline,cubic_bspline"))
local g, rho, E = 9.81, 1000, 1e6
local cell = dim == 2 and 0.025 or 0.05

-- one run: the block on face `face` (bottom or side), gravity at theta from
-- the face normal pointing along +x' (the sliding direction)
local function run(o)
  local th = math.rad(o.theta)
  local gn, gt = -g * math.cos(th), g * math.sin(th) -- into the face, along it
  local size, lo, hi, gravity, v0, along, normal
  if o.face == "side" then -- the wall is xmin; the block slides along +y
    size = dim == 2 and { 0.5, 2 } or { 0.5, 2, 0.5 }
    lo = dim == 2 and { 0, 0.1 } or { 0, 0.1, 0.15 }
    hi = dim == 2 and { 0.2, 0.5 } or { 0.2, 0.5, 0.35 }
    gravity = dim == 2 and { gn, gt } or { gn, gt, 0 }
    v0 = dim == 2 and { 0, o.v0 or 0 } or { 0, o.v0 or 0, 0 }
    along, normal = 2, 1
  else
    size = dim == 2 and { 2, 0.5 } or { 2, 0.5, 0.5 }
    lo = dim == 2 and { 0.1, 0 } or { 0.1, 0.15, 0 }
    hi = dim == 2 and { 0.5, 0.2 } or { 0.5, 0.35, 0.2 }
    gravity = dim == 2 and { gt, gn } or { gt, 0, gn }
    v0 = dim == 2 and { o.v0 or 0, 0 } or { o.v0 or 0, 0, 0 }
    along, normal = 1, dim
  end
  local floor = { "friction", mu = o.mu }
  local boundary = o.face == "side" and { all = "slip", xmin = floor, xmax = "free" }
                   or { all = "slip", bottom = floor, top = "free" }
  local transfer, holds = T.strategy(o.strategy)
  local sim = mpm.simulation{ dim = dim, grid = { size = size, cell = cell }, shape = o.shape,
                              scheme = { transfer = transfer, holds = holds },
                              gravity = gravity, boundary = boundary, dt = { a_tau = 0.2 },
                              diagnostics = false, thermo = 0, progress = false }
  sim:add_particles(mpm.box{ min = lo, max = hi },
                    { material = mpm.material.linear_elastic{ density = rho, E = E, nu = 0.3 },
                      per_cell = 2 ^ dim, velocity = v0 })
  local d0 = sim:diagnostics()
  sim:run{ time = o.time }
  local d = sim:diagnostics()
  local mass = rho * 0.4 * 0.2 * (dim == 3 and 0.2 or 1)
  return { dist = d.center_of_mass[along] - d0.center_of_mass[along], v = d.com_velocity[along],
           vn = d.com_velocity[normal], ek0 = d0.E_kinetic, ek = d.E_kinetic, eel = d.E_elastic,
           wfr = d.W_friction, N = mass * g * math.cos(th) }
end

local function label(o)
  return string.format("%dD %s %s %s theta %g mu %g", dim, o.strategy, o.shape, o.face, o.theta, o.mu)
end

-- W_friction = -mu N d and no self-excited vibration: the worst figures
local energy = { wfr = 0, eel = 0 }
local function check_energy(o, r, ek_ref)
  local w = -o.mu * r.N * r.dist
  local off, eel = math.abs(r.wfr / w - 1), r.eel / ek_ref
  if off > energy.wfr then energy.wfr, energy.wfr_case = off, label(o) end
  if eel > energy.eel then energy.eel, energy.eel_case = eel, label(o) end
  if o.strategy == "PIC" then
    T.check(off <= 0.05, "%s: W_friction %.4g J, -mu N d = %.4g J (%.1f %% off)", label(o), r.wfr, w, 100 * (r.wfr / w - 1))
    T.check(eel <= 0.01, "%s: elastic energy %.3g J above 1 %% of the kinetic energy %.3g J", label(o), r.eel, ek_ref)
  end
  if mpm.param("verbose", false) then
    print(string.format("%-60s W_fr %.4g J vs -mu N d %.4g J (%+.1f %%), E_el / E_k %.2f %%", label(o), r.wfr, w,
                        100 * (r.wfr / w - 1), 100 * eel))
  end
end

local worst = { slide = 0, stop = 0, creep = 0 }
for _, shape in ipairs(shapes) do
  for _, strategy in ipairs(strategies) do
    for _, case in ipairs{ { theta = 30, mu = 0.3, face = "bottom" }, { theta = 40, mu = 0.5, face = "bottom" },
                           { theta = 30, mu = 0.3, face = "side" } } do
      local o = { strategy = strategy, shape = shape, theta = case.theta, mu = case.mu, face = case.face, time = 0.6 }
      local r = run(o)
      local a = 2 * r.dist / o.time ^ 2
      local exact = g * (math.sin(math.rad(o.theta)) - o.mu * math.cos(math.rad(o.theta)))
      worst.slide = math.max(worst.slide, math.abs(a / exact - 1))
      T.check(math.abs(a - exact) <= 0.03 * exact, "%s: a = %.4f m/s^2, closed form %.4f (%.1f %% off)", label(o), a,
              exact, 100 * (a / exact - 1))
      check_energy(o, r, r.ek)
    end
    local o = { strategy = strategy, shape = shape, theta = 10, mu = 0.3, face = "bottom", time = 0.4 }
    local r = run(o)
    local free = 0.5 * g * math.sin(math.rad(o.theta)) * o.time ^ 2
    worst.creep = math.max(worst.creep, math.abs(r.dist) / free)
    T.check(math.abs(r.dist) < 0.01 * free, "%s: the block should stick, but crept %.3g m (frictionless %.3g m)",
            label(o), r.dist, free)
    o = { strategy = strategy, shape = shape, theta = 0, mu = 0.3, face = "bottom", v0 = 2 }
    local stop = o.v0 ^ 2 / (2 * o.mu * g)
    o.time = 1.3 * o.v0 / (o.mu * g)
    r = run(o)
    worst.stop = math.max(worst.stop, math.abs(r.dist / stop - 1))
    T.check(math.abs(r.dist - stop) <= 0.03 * stop, "%s: stopped after %.4f m, closed form %.4f m (%.1f %% off)",
            label(o), r.dist, stop, 100 * (r.dist / stop - 1))
    T.check(math.abs(r.v) < 0.01 * o.v0, "%s: not at rest: %.3g m/s", label(o), r.v)
    check_energy(o, r, r.ek0)
  end
end
T.expect{ id = string.format("friction.%dd.slide", dim), what = string.format("%dD: worst |a / a_exact - 1| of the slides", dim),
          value = 100 * worst.slide, max = 3, unit = "%" }
T.expect{ id = string.format("friction.%dd.stop", dim), what = string.format("%dD: worst stopping-distance error", dim),
          value = 100 * worst.stop, max = 3, unit = "%" }
T.expect{ id = string.format("friction.%dd.creep", dim), what = string.format("%dD: worst creep of a sticking block", dim),
          value = 100 * worst.creep, max = 1, unit = "% of frictionless" }
T.expect{ id = string.format("friction.%dd.W_friction", dim), asserted = false,
          what = string.format("%dD: worst |W_friction / (-mu N d) - 1| (%s)", dim, energy.wfr_case or "-"),
          value = 100 * energy.wfr, max = 5, unit = "%" }
T.expect{ id = string.format("friction.%dd.elastic", dim), asserted = false,
          what = string.format("%dD: worst E_el / E_k at the end or at release (%s)", dim, energy.eel_case or "-"),
          value = 100 * energy.eel, max = 1, unit = "%" }
T.done("friction")
