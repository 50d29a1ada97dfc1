-- Decks that make or load particles during a run, the same on 1, 2 and 3
-- processes (tests/parallel/equivalence.py runs them under mpirun and
-- compares the diagnostics and the particles by id). The slabs are cut
-- along y, re-cut when the counts drift (the default policy):
--   --set case=source: two inflow sources into a pool of a viscous liquid,
--     one through the left face over the cuts (its inlet box spans them),
--     one pouring down through them from mid-height;
--   --set case=split: a soft bar along y stretching to about twice its
--     length, its particles split as they stretch, children landing on
--     either side of the cuts;
--   --set case=point: an elastic column on a friction floor under point
--     forces: a total force shared by the points of a region that lies
--     on every process, then a traction on one side added mid-run (the
--     points chosen when the run is spread), a load factor ramped by a
--     hook, and the forces cleared for the last steps.
-- --set rebalance=N re-cuts the slabs every N steps whatever the counts;
-- --set load=FILE continues the source or split case from a checkpoint
-- (tests/parallel/restart.py).
-- Writes the diagnostics every step (NAME.csv) and the final state
-- (NAME.h5, sim:save: every particle, in the order of their ids).
local case = mpm.param("case", "source")
local steps = mpm.param("steps", 400)
local name = mpm.param("name", case)
local rebalance = mpm.param("rebalance", 0)
local load = mpm.param("load", "")
local common = { thermo = 0, diagnostics = name .. ".csv", diagnostics_every = 1, series = false }
-- the case's simulation, or the checkpoint `load` continued
local function simulation(opts)
  if load ~= "" then return mpm.load(load, { thermo = 0, diagnostics = name .. ".csv" }), true end
  for k, v in pairs(common) do opts[k] = v end
  return mpm.simulation(opts), false
end
local sim, run -- the simulation and how it runs

if case == "source" then
  local water = mpm.material.newtonian{ density = 1000, viscosity = 1, sound_speed = 10 }
  local loaded
  sim, loaded = simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.025 }, gravity = { 0, -9.81 },
    scheme = { transfer = "FLIP", stress_update = "USL" }, boundary = { all = "slip", top = "free" },
    dt = { cfl = 0.4 } }
  if not loaded then
    sim:add_particles(mpm.box{ min = { 0.3, 0 }, max = { 1, 0.3 } }, { material = water, per_axis = 2,
                                                                     placement = "regular" })
  end
  -- added again to a loaded simulation: each takes up its state by name
  sim:add_source{ name = "side", region = mpm.box{ min = { 0, 0.05 }, max = { 0.1, 0.35 } }, material = water,
                  velocity = { 1.0, 0 } }
  sim:add_source{ name = "drop", region = mpm.box{ min = { 0.6, 0.45 }, max = { 0.7, 0.55 } }, material = water,
                  face = "ymax", velocity = function(t) return 0, -math.min(t / 0.05, 1) end }
  run = function() sim:run{ steps = steps } end
elseif case == "split" then
  -- soft (its stress small against its inertia): it keeps stretching
  local bar = mpm.material.neo_hookean{ density = 1000, E = 10, nu = 0.3 }
  local loaded
  sim, loaded = simulation{ dim = 2, grid = { origin = { 0, -1 }, size = { 0.5, 2 }, cell = 0.025 },
    scheme = { transfer = "TPIC", stress_update = "MUSL" }, dt = { fixed = 2.5e-3 }, gravity = { 0, 0 },
    split = { stretch = 1.3, max_level = 3 } }
  -- stretching along y at 2 /s, drifting at (0.05, 0.1) m/s and turning at
  -- 0.1 rad/s (no diagnostic zero by symmetry: those carry only round-off)
  if not loaded then
    sim:add_particles(mpm.box{ min = { 0.2, -0.3 }, max = { 0.3, 0.3 } }, { material = bar, per_axis = 2,
      velocity = function(x, y) return 0.05 - 0.1 * y, 0.1 + 2 * y + 0.1 * (x - 0.25) end })
  end
  run = function() sim:run{ steps = steps } end
elseif case == "point" then
  local rubber = mpm.material.linear_elastic{ density = 1000, E = 2e5, nu = 0.3 }
  assert(load == "", "the point case starts from its deck only")
  sim = simulation{ dim = 2, grid = { size = { 1, 1.5 }, cell = 0.025 }, gravity = { 0, -9.81 },
    scheme = { transfer = "FLIP", stress_update = "USF" }, dt = { cfl = 0.5 },
    boundary = { left = "slip", right = "slip", bottom = { "friction", mu = 0.4 }, top = "free" } }
  sim:add_particles(mpm.box{ min = { 0.3, 0 }, max = { 0.6, 1.0 } }, { material = rubber, per_axis = 2 })
  -- a column of points from the floor to the top: on every process
  local n = sim:point_force{ region = mpm.box{ min = { 0.5, 0 }, max = { 0.55, 1.0 } }, force = { 40, 20 } }
  sim:hook{ every_steps = 1, fn = function(s) s:load_factor(math.min(s:step() / 100, 1)) end }
  run = function()
    local third = math.floor(steps / 3)
    sim:run{ steps = third }
    -- the points of the left face, each on its own process now
    local m = sim:point_force{ region = mpm.box{ min = { 0.2, 0.1 }, max = { 0.32, 0.9 } }, traction = { 300, 0 } }
    print(string.format("point forces on %d points, then %d more", n, m))
    sim:run{ steps = third }
    sim:clear_forces()
    sim:run{ steps = steps - 2 * third }
  end
else
  error("case must be source, split or point, got " .. tostring(case))
end
if rebalance > 0 then sim:set_parallel{ rebalance_every = rebalance, imbalance = 1.0 } end
run()
local par = dofile(mpm.deck_dir .. "/finish.lua")(sim, name)
