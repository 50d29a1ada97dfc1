-- Rigid walls survive a checkpoint bit for bit: a block on a friction plane
-- at 30 degrees pushed by a turning plate moved by a function of time, run
-- straight for 0.2 s and stopped at 0.1 s, saved, loaded (the plate's
-- function set again) and run on. Positions, velocities, stresses, W_walls
-- and every wall's impulse, work and pivot must agree exactly (the plane with
-- gap_check, which the checkpoint keeps).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local scheme = mpm.param("scheme", "APIC")
local function build()
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.6, 1.2 }, cell = 0.025 }, shape = "quadratic_bspline",
                              scheme = scheme, gravity = { 0, -9.81 }, boundary = { all = "slip", top = "free" },
                              dt = { a_tau = 0.2 }, diagnostics = false, thermo = 0, progress = false }
  local th = math.rad(30)
  sim:add_wall{ name = "plane", shape = "plane", point = { 0.1, 0.9 }, normal = { math.sin(th), math.cos(th) },
                kind = "friction", mu = 0.3, gap_check = true }
  sim:add_wall{ name = "plate", shape = "polygon", vertices = { { 1.3, 0.05 }, { 1.4, 0.05 }, { 1.4, 0.35 }, { 1.3, 0.35 } },
                kind = "friction", mu = 0.2, velocity = function(t) return { -0.1 * t, 0 } end, omega = 0.05 }
  sim:add_particles(mpm.box{ min = { 0.3, 0.85 }, max = { 0.5, 1.0 } },
                    { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }, per_cell = 4 })
  sim:add_particles(mpm.box{ min = { 0.9, 0.0 }, max = { 1.3, 0.2 } },
                    { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }, per_cell = 4 })
  return sim
end
local straight = build()
straight:run{ steps = 600 }
local first = build()
first:run{ steps = 300 }
local path = first:save("walls_restart.h5")
local again = mpm.load(path)
again:set_wall("plate", { velocity = function(t) return { -0.1 * t, 0 } end })
T.check(again:wall("plane").gap_check and not again:wall("plate").gap_check, "gap_check lost in the checkpoint")
again:run{ steps = 300 }
T.check(again:step() == straight:step(), "steps %d and %d", again:step(), straight:step())
for i = 1, straight:particle_count() do
  local a, b = straight:particle(i), again:particle(i)
  for d = 1, 2 do
    T.check(a.x[d] == b.x[d] and a.v[d] == b.v[d], "particle %d differs after the restart", i)
  end
  for k = 1, 6 do T.check(a.stress[k] == b.stress[k], "particle %d stress differs after the restart", i) end
end
for _, name in ipairs{ "plane", "plate" } do
  local a, b = straight:wall(name), again:wall(name)
  for d = 1, 2 do
    T.check(a.impulse[d] == b.impulse[d] and a.pivot[d] == b.pivot[d], "wall %s differs after the restart", name)
  end
  T.check(a.work == b.work and a.work_friction == b.work_friction, "wall %s work differs after the restart", name)
  T.check(a.work_friction < 0, "wall %s: no friction", name)
end
T.check(straight:diagnostics().W_walls == again:diagnostics().W_walls, "W_walls differs after the restart")
T.done("walls_restart")
