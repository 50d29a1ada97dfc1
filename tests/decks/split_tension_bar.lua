-- A large-deformation tension bar (tension_bar.lua): a soft elastic bar
-- pulled to 3 times its length, whose exact motion is the uniform
-- stretch. With 2 x 2 particles per cell
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

local B = dofile(mpm.deck_dir .. "/tension_bar.lua")
local L0 = B.L0

local function build(split, scheme, name) return B.build{ split = split, scheme = scheme, name = name } end

local function run(split, scheme)
  local sim, nbar = build(split, scheme)
  local mass0 = sim:diagnostics().mass
  sim:run{ time = B.T_END }
  return sim, nbar, mass0
end

local inspect = B.inspect

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
