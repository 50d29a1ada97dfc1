-- Rigid walls (sim:add_wall) against closed forms, 2D, quadratic B-splines.
--
-- incline  an elastic block (0.4 m x 0.2 m, E = 1 MPa, nu = 0.3,
--          rho = 1000 kg/m^3, 2 x 2 points per 0.025 m cell) on a friction
--          plane tilted by theta (not grid-aligned), gravity vertical:
--   slide  (35 deg, mu = 0.3; 25 deg, mu = 0.2; 0.6 s): a from the centre of
--          mass along the plane, x = a t^2 / 2, against
--          g (sin theta - mu cos theta) within 3 %;
--   stick  (25 deg, mu = 0.8 > tan 25, 0.4 s, seeded with the stress of an
--          infinite slope, 1.2 m long): creep below 1 % of the frictionless
--          distance, the plane's reaction averaged over 0.2 s equal to the
--          weight's components within 3 %, and the normal stress at
--          mid-height of the middle third (averaged over those 0.2 s; the
--          block vibrates, undamped) within 3 % of the lithostatic
--          -rho g cos(theta) (H - h). Reported, not asserted: the shear
--          stress there against the infinite slope's rho g sin(theta) (H - h)
--          (a finite block with free ends is not an infinite slope: the
--          middle third of one six heights long carries a few per cent more).
--   rest   (--set only=rest) the stick case alone, with --set length=L (m),
--          --set rest_cell=h (m) and --set average=s (the averaging window):
--          a block long enough for its middle to be the infinite slope, on
--          cells fine enough, has both stresses there within 3 % (asserted),
--          e.g. length 2.4 (twelve heights), rest_cell 0.0125, average 0.6;
--          --set face=true puts it on a friction face (gravity tilted).
-- face     a friction plane through a row of nodes (gravity tilted by 35 deg,
--          mu = 0.3, 2000 steps) slides as the friction face, to 1e-6.
-- plate    a plate wall (velocity 0.05 m/s) pushes a block along a slip floor
--          (0.3 s): the impulse the plate took equals minus the block's
--          momentum (1 %), W_walls is the plate's work, and under FLIP W_MPM
--          stays below 1 % of it (reported for the others).
--   --set strategies=FLIP,APIC,...  --set only=rest
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local list = T.list
local strategies = list(mpm.param("strategies", "FLIP,APIC,XPIC(2)"))
local g, rho, E, cell = 9.81, 1000, 1e6, 0.025
local L, H = 0.4, 0.2

local only = mpm.param("only", "")
local rest_length, rest_cell = mpm.param("length", 1.2), mpm.param("rest_cell", cell)
local rest_average = mpm.param("average", 0.2) -- s, the window the stresses and the reaction are averaged over
local rest_face = mpm.param("face", false) -- the block at rest on a friction face, gravity tilted, instead

-- the grid holds the incline's blocks up to rest_length long
local function simulation(scheme, gravity, h, bottom)
  local width = math.max(2.0, math.ceil(0.5 + rest_length))
  return mpm.simulation{ dim = 2, grid = { size = { width, 1.6 }, cell = h or cell }, shape = "quadratic_bspline",
                         scheme = scheme, gravity = gravity, boundary = { all = "slip", top = "free", bottom = bottom },
                         dt = { a_tau = 0.2 }, diagnostics = false, thermo = 0, progress = false }
end

-- the block on a plane through p at theta: n out of the wall, t downhill;
-- with o.face on the bottom friction face, gravity tilted by theta
local function incline(o)
  local L = o.length or L
  local th = math.rad(o.theta)
  local n, t, p, sim
  if o.face then
    n, t, p = { 0, 1 }, { 1, 0 }, { 0.1, 0 }
    sim = simulation(o.strategy, { g * math.sin(th), -g * math.cos(th) }, o.cell, { "friction", mu = o.mu })
  else
    n, t, p = { math.sin(th), math.cos(th) }, { math.cos(th), -math.sin(th) }, { 0.1, 1.3 }
    sim = simulation(o.strategy, { 0, -g }, o.cell)
    sim:add_wall{ name = "incline", shape = "plane", point = p, normal = n, kind = "friction", mu = o.mu }
  end
  local function at(s, h) return { p[1] + s * t[1] + h * n[1], p[2] + s * t[2] + h * n[2] } end
  -- the infinite slope: sigma_nn = -rho g cos(theta) (H - h), sigma_nt = rho g sin(theta) (H - h)
  local function slope(x, y)
    local h = (x - p[1]) * n[1] + (y - p[2]) * n[2]
    local snn, snt = -rho * g * math.cos(th) * (H - h), rho * g * math.sin(th) * (H - h)
    local stt = 0.3 / 0.7 * snn
    local sxx = snn * n[1] * n[1] + stt * t[1] * t[1] + 2 * snt * n[1] * t[1]
    local syy = snn * n[2] * n[2] + stt * t[2] * t[2] + 2 * snt * n[2] * t[2]
    local sxy = snn * n[1] * n[2] + stt * t[1] * t[2] + snt * (n[1] * t[2] + t[1] * n[2])
    return { sxx, syy, 0.3 * (sxx + syy), sxy, 0, 0 }
  end
  sim:add_particles(mpm.polygon{ vertices = { at(0.2, 0), at(0.2 + L, 0), at(0.2 + L, H), at(0.2, H) } },
                    { material = mpm.material.linear_elastic{ density = rho, E = E, nu = 0.3 }, per_cell = 4,
                      stress = o.stressed and slope or nil })
  local d0 = sim:diagnostics()
  sim:run{ time = o.time }
  local d = sim:diagnostics()
  local dx = { d.center_of_mass[1] - d0.center_of_mass[1], d.center_of_mass[2] - d0.center_of_mass[2] }
  return sim, dx[1] * t[1] + dx[2] * t[2], n, t, p
end

local function label(o) return string.format("%s theta %g mu %g", o.strategy, o.theta, o.mu) end
local worst = { face = 0, slide = 0, creep = 0, stress = 0, shear = 0, reaction = 0, impulse = 0, budget = 0 }

-- the mean sigma_nn and sigma_nt of the middle third, with the slope's
local function middle_stress(o, sim, n, t, p, sum)
  local L = o.length
  local th = math.rad(o.theta)
  for i = 1, sim:particle_count() do
    local q = sim:particle(i)
    local px, py = q.x[1], q.x[2]
    local along = (px - p[1]) * t[1] + (py - p[2]) * t[2]
    local h = (px - p[1]) * n[1] + (py - p[2]) * n[2]
    if along > 0.2 + L / 3 and along < 0.2 + 2 * L / 3 and math.abs(h - 0.5 * H) < 0.25 * H then
      local sxx, syy, sxy = q.stress[1], q.stress[2], q.stress[4]
      sum[1] = sum[1] + sxx * n[1] * n[1] + syy * n[2] * n[2] + 2 * sxy * n[1] * n[2]
      sum[2] = sum[2] + sxx * n[1] * t[1] + syy * n[2] * t[2] + sxy * (n[1] * t[2] + t[1] * n[2])
      sum[3] = sum[3] - rho * g * math.cos(th) * (H - h)
      sum[4] = sum[4] + rho * g * math.sin(th) * (H - h)
    end
  end
end

-- the slides down the two planes
local function slides(strategy)
  for _, case in ipairs{ { theta = 35, mu = 0.3 }, { theta = 25, mu = 0.2 } } do
    local o = { strategy = strategy, theta = case.theta, mu = case.mu, time = 0.6 }
    local _, s = incline(o)
    local a = 2 * s / o.time ^ 2
    local exact = g * (math.sin(math.rad(o.theta)) - o.mu * math.cos(math.rad(o.theta)))
    worst.slide = math.max(worst.slide, math.abs(a / exact - 1))
    T.check(math.abs(a - exact) <= 0.03 * exact, "%s: a = %.4f m/s^2, closed form %.4f (%.1f %% off)", label(o), a, exact,
            100 * (a / exact - 1))
  end
end

-- the block that sticks: its creep, the plane's reaction and the stresses
local function at_rest(strategy)
  local o = { strategy = strategy, theta = 25, mu = 0.8, time = 0.4, stressed = true, length = rest_length,
              cell = rest_cell, face = rest_face }
  local sim, s, n, t, p = incline(o)
  local free = 0.5 * g * math.sin(math.rad(o.theta)) * o.time ^ 2
  worst.creep = math.max(worst.creep, math.abs(s) / free)
  T.check(math.abs(s) < 0.01 * free, "%s: the block should stick, but crept %.3g m (frictionless %.3g m)", label(o), s,
          free)
  -- the stress averaged over `average` s more (the block vibrates,
  -- undamped), and the plane's mean reaction then against the weight
  local sum, J0 = { 0, 0, 0, 0 }, not o.face and sim:wall("incline").impulse
  for _ = 1, math.floor(rest_average / 0.01 + 0.5) do
    sim:run{ time = 0.01 }
    middle_stress(o, sim, n, t, p, sum)
  end
  if not o.face then
    local J1, W = sim:wall("incline").impulse, rho * o.length * H * g
    local F = { (J1[1] - J0[1]) / rest_average, (J1[2] - J0[2]) / rest_average }
    local th = math.rad(o.theta)
    local fn, ft = -(F[1] * n[1] + F[2] * n[2]), F[1] * t[1] + F[2] * t[2]
    local rn, rt = math.abs(fn / (W * math.cos(th)) - 1), math.abs(ft / (W * math.sin(th)) - 1)
    worst.reaction = math.max(worst.reaction, rn, rt)
    T.check(rn <= 0.03 and rt <= 0.03, "%s: mean reaction %.4g N/m normal, %.4g along (weight: %.4g, %.4g)",
            label(o), fn, ft, W * math.cos(th), W * math.sin(th))
  end
  local enn, ent = math.abs(sum[1] / sum[3] - 1), math.abs(sum[2] / sum[4] - 1)
  worst.stress = math.max(worst.stress, enn)
  worst.shear = math.max(worst.shear, ent)
  print(string.format("%s, block %g m long on %g m cells (%s), at rest: sigma_nn %+.2f %% off the lithostatic, "
                      .. "sigma_nt %+.2f %% off the infinite slope's", label(o), o.length, o.cell,
                      o.face and "friction face" or "wall",
                      100 * (sum[1] / sum[3] - 1), 100 * (sum[2] / sum[4] - 1)))
  T.check(enn <= 0.03, "%s: mean sigma_nn at mid-height %.4g Pa, lithostatic %.4g", label(o), sum[1], sum[3])
end

if only == "rest" then
  for _, strategy in ipairs(strategies) do at_rest(strategy) end
  local what = string.format("block %g m long (%g heights) on %g m cells%s, at rest: mean %%s at mid-height of the "
                             .. "middle third off the %%s", rest_length, rest_length / H, rest_cell,
                             rest_face and " on a friction face" or "")
  T.expect{ id = "walls.rest.normal", value = 100 * worst.stress, max = 3, unit = "%",
            what = string.format(what, "sigma_nn", "lithostatic") }
  T.expect{ id = "walls.rest.shear", value = 100 * worst.shear, max = 3, unit = "%",
            what = string.format(what, "sigma_nt", "infinite slope's") }
  T.expect{ id = "walls.rest.creep", value = 100 * worst.creep, max = 1, unit = "% of frictionless",
            what = "its creep" }
  T.done("walls (at rest)")
  return
end
for _, strategy in ipairs(strategies) do
  slides(strategy)
  at_rest(strategy)
end

-- a grid-aligned plane through a row of nodes is a friction face: the block
-- tilted gravity on each, the same slide to 1e-6
for _, strategy in ipairs(strategies) do
  local th, mu = math.rad(35), 0.3
  local gravity = { g * math.sin(th), -g * math.cos(th) }
  local slid = {}
  for _, face in ipairs{ true, false } do
    local sim = mpm.simulation{ dim = 2, grid = { size = { 2.0, 0.8 }, cell = cell }, shape = "quadratic_bspline",
                                scheme = strategy, gravity = gravity, dt = { a_tau = 0.2 }, diagnostics = false,
                                thermo = 0, progress = false,
                                boundary = { all = "slip", top = "free", bottom = face and { "friction", mu = mu } or nil } }
    local y0 = face and 0 or 0.3
    if not face then sim:add_wall{ name = "floor", shape = "plane", point = { 0, y0 }, normal = { 0, 1 }, kind = "friction", mu = mu } end
    sim:add_particles(mpm.box{ min = { 0.2, y0 }, max = { 0.2 + L, y0 + H } },
                      { material = mpm.material.linear_elastic{ density = rho, E = E, nu = 0.3 }, per_cell = 4 })
    local c0 = sim:diagnostics().center_of_mass[1]
    sim:run{ steps = 2000 }
    slid[#slid + 1] = sim:diagnostics().center_of_mass[1] - c0
  end
  local off = math.abs(slid[2] / slid[1] - 1)
  worst.face = math.max(worst.face, off)
  T.check(off <= 1e-6, "%s: a grid-aligned friction plane slid %.9g m, the friction face %.9g m", strategy, slid[2],
          slid[1])
end

-- a plate pushing a block along a slip floor
for _, strategy in ipairs(strategies) do
  local sim = simulation(strategy, { 0, -g })
  local v = 0.05
  sim:add_wall{ name = "plate", shape = "box", min = { 0.0, 0.0 }, max = { 0.1, 0.6 }, kind = "slip",
                velocity = { v, 0 } }
  sim:add_particles(mpm.box{ min = { 0.1, 0 }, max = { 0.1 + L, H } },
                    { material = mpm.material.linear_elastic{ density = rho, E = E, nu = 0.3 }, per_cell = 4 })
  sim:run{ time = 0.3 }
  local d, w = sim:diagnostics(), sim:wall("plate")
  local off = math.abs(w.impulse[1] + d.momentum[1]) / math.abs(d.momentum[1])
  worst.impulse = math.max(worst.impulse, off)
  T.check(off <= 0.01, "%s plate: impulse on the plate %.5g N s, block momentum %.5g (%.2f %% off)", strategy,
          w.impulse[1], d.momentum[1], 100 * off)
  T.check(math.abs(d.W_walls - w.work) <= 1e-12 * math.abs(w.work), "W_walls %.6g differs from the plate's work %.6g",
          d.W_walls, w.work)
  local budget = math.abs(d.W_MPM) / w.work
  T.check(w.work > 0, "%s plate: the plate did no work (%.4g J/m)", strategy, w.work)
  if strategy == "FLIP" then
    worst.budget = math.max(worst.budget, budget)
  else
    worst.other = math.max(worst.other or 0, budget)
  end
end

T.expect{ id = "walls.incline.slide", what = "worst |a / a_exact - 1| of the slides on an inclined plane",
          value = 100 * worst.slide, max = 3, unit = "%" }
T.expect{ id = "walls.incline.creep", what = "worst creep of a block sticking on an inclined plane",
          value = 100 * worst.creep, max = 1, unit = "% of frictionless" }
T.expect{ id = "walls.incline.reaction", what = "block at rest: worst mean reaction off the weight's components",
          value = 100 * worst.reaction, max = 3, unit = "%" }
T.expect{ id = "walls.incline.stress", value = 100 * worst.stress, max = 3, unit = "%",
          what = "block at rest: mean sigma_nn at mid-height of the middle third off the lithostatic" }
T.expect{ id = "walls.incline.shear", asserted = false, value = 100 * worst.shear, max = 3, unit = "%",
          what = "block at rest: mean sigma_nt at mid-height of the middle third off the infinite slope's" }
T.expect{ id = "walls.incline.face", what = "grid-aligned friction plane against the friction face: slide off",
          value = worst.face, max = 1e-6, unit = "" }
T.expect{ id = "walls.plate.impulse", what = "plate: |impulse + block momentum| / |momentum|",
          value = 100 * worst.impulse, max = 1, unit = "%" }
T.expect{ id = "walls.plate.budget", what = "plate, FLIP: |W_MPM| / plate work", value = 100 * worst.budget, max = 1,
          unit = "%" }
T.expect{ id = "walls.plate.budget_other", asserted = false, value = 100 * (worst.other or 0), unit = "%",
          what = "plate, the other strategies: |W_MPM| / plate work (their own dissipation and the inelastic contact)" }
T.done("walls")
