-- A large-deformation tension bar: a soft elastic (neo-Hookean) bar 1 m
-- long is pulled to 3 times its length by two heavy grips moving apart at
-- 0.5 m/s; it starts with the matching linear velocity profile, and its
-- stress (E = 10 Pa) stays small against its inertia (rho V^2 = 250 Pa), so
-- the exact motion is the uniform stretch. With 2 x 2 particles per cell
-- the particles of standard MPM end 1.5 cells apart along the bar: cells
-- inside the bar are left with no particle, and the bar separates
-- numerically. With particle splitting (simulation{split}, doc/numerics.md
-- "Particle splitting") a particle whose domain stretched past 1.3 times
-- its initial half-width splits, and the bar stays continuous.
--
-- Asserted, with APIC: without splitting, empty cells appear inside the bar
-- (what splitting is for: if standard MPM kept the bar whole this test would
-- say nothing); with splitting none does; splitting conserves the mass; the
-- bar reaches 3 times its length either way. Reported: the same with FLIP,
-- whose children keep their parent's velocity (doc/numerics.md: they move
-- apart only by the grid's velocity).
local T = dofile(mpm.deck_dir .. "/testlib.lua")

local CELL, L0, H, V_END = 0.025, 1.0, 0.1, 0.5
local T_END = (3 - 1) * L0 / (2 * V_END) -- the grips 3 L0 apart (inner faces)
local bar = mpm.material.neo_hookean{ density = 1000, E = 10, nu = 0.3, name = "bar" }
local grip = mpm.material.neo_hookean{ density = 1e9, E = 10, nu = 0.3, name = "grip" }

local function build(split, scheme, name)
  local sim = mpm.simulation{
    dim = 2, grid = { origin = { -2, 0 }, size = { 4, 0.25 }, cell = CELL },
    scheme = scheme, dt = { fixed = 2.5e-3 }, split = split, thermo = 0, diagnostics = false, series = false,
    name = name or (split and "split_" or "standard_") .. scheme,
  }
  local function velocity(x) return V_END * math.max(-1, math.min(1, x / (0.5 * L0))), 0 end
  sim:add_particles(mpm.box{ min = { -0.5 * L0, 0.075 }, max = { 0.5 * L0, 0.075 + H } },
                    { material = bar, per_axis = 2, velocity = velocity })
  local nbar = sim:particle_count()
  sim:add_particles(mpm.box{ min = { -0.5 * L0 - 0.1, 0.075 }, max = { -0.5 * L0, 0.075 + H } },
                    { material = grip, per_axis = 2, velocity = { -V_END, 0 } })
  sim:add_particles(mpm.box{ min = { 0.5 * L0, 0.075 }, max = { 0.5 * L0 + 0.1, 0.075 + H } },
                    { material = grip, per_axis = 2, velocity = { V_END, 0 } })
  return sim, nbar
end

local function run(split, scheme)
  local sim, nbar = build(split, scheme)
  local mass0 = sim:diagnostics().mass
  sim:run{ time = T_END }
  return sim, nbar, mass0
end

-- the cells of the bar's two middle rows between the grips' inner faces
-- that hold no particle, and the bar's length and mean axial stress
local function inspect(sim)
  local lo, hi, n = math.huge, -math.huge, sim:particle_count()
  local cells, sxx, vol = {}, 0, 0
  for i = 1, n do
    local p = sim:particle(i)
    if p.material == 2 then
      if p.x[1] < 0 then lo = math.min(lo, p.x[1]) else hi = math.max(hi, p.x[1]) end
    end
  end
  local grip_lo, grip_hi = -math.huge, math.huge
  for i = 1, n do
    local p = sim:particle(i)
    if p.material == 2 then
      if p.x[1] < 0 then grip_lo = math.max(grip_lo, p.x[1]) else grip_hi = math.min(grip_hi, p.x[1]) end
    else
      local cx, cy = math.floor((p.x[1] + 2) / CELL), math.floor(p.x[2] / CELL)
      cells[cx * 1000 + cy] = true
      sxx, vol = sxx + p.stress[1] * p.volume, vol + p.volume
    end
  end
  local empty = 0
  local first, last = math.floor((grip_lo + 2) / CELL) + 2, math.floor((grip_hi + 2) / CELL) - 2
  for cx = first, last do
    for _, cy in ipairs{ 4, 5 } do -- y in [0.1, 0.15]: the middle of the bar (0.075 to 0.175 at the start)
      if not cells[cx * 1000 + cy] then empty = empty + 1 end
    end
  end
  return { empty = empty, length = grip_hi - grip_lo, stress = sxx / vol, particles = n, span = hi - lo }
end

local results = {}
local SPLIT = { stretch = 1.3, max_level = 4 }
for _, case in ipairs{ { "standard", false, "APIC" }, { "split", SPLIT, "APIC" }, { "split_FLIP", SPLIT, "FLIP" },
                       { "standard_FLIP", false, "FLIP" } } do
  local sim, nbar, mass0 = run(case[2], case[3])
  local r = inspect(sim)
  local d = sim:diagnostics()
  print(string.format("%-13s bar %.3f m long (grip faces), %d particles (bar %d at the start), %d empty cells " ..
                      "in the bar", case[1], r.length, r.particles, nbar, r.empty))
  T.close(d.mass, mass0, 1e-12, case[1] .. ": mass")
  T.close(r.length, 3 * L0, 0.02, case[1] .. ": length between the grips")
  results[case[1]] = r
end
T.expect{ id = "split_tension_bar.gaps_standard", what = "empty cells inside the bar at 3 L0, APIC without splitting",
          value = results.standard.empty, min = 1 }
T.expect{ id = "split_tension_bar.gaps_split", what = "empty cells inside the bar at 3 L0, APIC with splitting",
          value = results.split.empty, max = 0 }
T.expect{ id = "split_tension_bar.gaps_standard_flip", what = "empty cells inside the bar at 3 L0, FLIP without splitting",
          value = results.standard_FLIP.empty, asserted = false }
T.expect{ id = "split_tension_bar.gaps_split_flip", what = "empty cells inside the bar at 3 L0, FLIP with splitting",
          value = results.split_FLIP.empty, asserted = false }
-- most bar particles split twice (those by the grips stretch less)
T.check(results.split.particles >= 3 * 640 + 128, "splitting made only %d particles", results.split.particles)

-- a checkpoint in the middle of the splitting: saved, loaded, run on = the
-- straight run, bit for bit (the count changes on either side of it)
local function same_state(a, b, label)
  T.check(a:particle_count() == b:particle_count(), "%s: %d vs %d particles", label, a:particle_count(),
          b:particle_count())
  for _, f in ipairs{ "velocity", "displacement", "stress", "id", "mass", "volume", "deformation_gradient",
                      "split_domain", "split_level" } do
    local x, y = a:field(f), b:field(f)
    for i = 1, #x do
      if x[i] ~= y[i] then T.check(false, "%s: %s[%d] differs: %.17g vs %.17g", label, f, i, x[i], y[i]) end
    end
  end
  T.check(a:diagnostics().W_MPM == b:diagnostics().W_MPM, "%s: W_MPM differs", label)
end
local straight = build(SPLIT, "APIC", "straight")
straight:run{ steps = 300 }
local first = build(SPLIT, "APIC", "first")
first:run{ steps = 100 }
local mid = first:particle_count()
first:save("split_mid.h5")
local loaded = mpm.load("split_mid.h5", { thermo = 0, diagnostics = false })
loaded:run{ steps = 200 }
T.check(loaded:particle_count() > mid, "no particle split after the checkpoint (%d particles)", mid)
T.check(mid > 768, "no particle split before the checkpoint")
same_state(straight, loaded, "checkpoint")
print(string.format("checkpoint at step 100 (%d particles), step 300: %d particles, bit for bit", mid,
                    loaded:particle_count()))
T.done("split_tension_bar")
