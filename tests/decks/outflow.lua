-- Particles leaving through an open face with on_leave = "delete".
-- An elastic block falls under gravity through the free bottom face of a
-- 1 m x 1 m grid (the other faces are slip walls). With the default policy
-- the run would stop at the first particle below y = 0 (tests/bad/left_grid.lua);
-- here every particle that leaves is deleted and booked as outflow:
--  1. mass is conserved: remaining mass + outflow mass = initial mass (1e-12);
--  2. the energy balance does not jump when particles go. W_MPM is not zero
--     in free fall: the step's position update gives the discrete trajectory
--     y_n = y_0 - g dt^2 n (n + 1) / 2 of tests/decks/free_fall.lua, so a
--     particle that has made n steps carries E_k + E_g - E_0 = -m g^2 dt^2 n / 2.
--     W_MPM (which adds back the outflow's E_k + E_g + E_el - W_pl) must equal
--     -g^2 dt^2 / 2 (sum over deleted particles of m n_deleted + m_left n),
--     to 1e-9 of the block's potential energy drop;
--  3. the whole block is gone at the end, and the count of deleted particles
--     equals the number seeded;
--  4. a checkpoint taken half-way keeps the policy and the outflow book, and the
--     run loaded from it ends in the same state as the straight run.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local g = 9.81
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }

local function make(depth, on_leave)
  local sim = mpm.simulation{ dim = 2, grid = { origin = { 0, -depth }, size = { 1, 1 + depth }, cell = 0.05 },
    gravity = { 0, -g }, boundary = { all = "slip", bottom = "free" }, scheme = "FLIP", dt = { fixed = 1e-3 },
    on_leave = on_leave, thermo = 0, diagnostics = false, series = false }
  sim:add_particles(mpm.box{ min = { 0.4, 0.1 }, max = { 0.6, 0.3 } }, { material = mat, per_axis = 2 })
  return sim
end

local sim = make(0, "delete")
local n0 = sim:particle_count()
local d0 = sim:diagnostics()
local m0 = d0.mass
local dt = 1e-3
-- step by step, booking the mass deleted at each step: sum of m n over the outflow
local out_mn, out_m = 0, 0
local function advance(steps)
  for _ = 1, steps do
    if sim:particle_count() == 0 then return end -- run{} refuses an empty simulation
    sim:run{ steps = 1 }
    local d = sim:diagnostics()
    out_mn = out_mn + (d.outflow_mass - out_m) * d.step
    out_m = d.outflow_mass
  end
end
local function expected_w_mpm(d) return -0.5 * g * g * dt * dt * (out_mn + d.mass * d.step) end
-- the block's bottom reaches y = 0 after sqrt(2 * 0.1 / g) = 0.143 s and its top after 0.247 s
advance(200)
local mid = sim:diagnostics()
T.check(mid.outflow_particles > 0 and mid.outflow_particles < n0,
        "half-way: %d of %d particles deleted, expected some but not all", mid.outflow_particles, n0)
T.close(mid.mass + mid.outflow_mass, m0, 1e-12, "remaining + outflow mass half-way")
T.expect{ id = "outflow.w_mpm_mid", what = "|W_MPM - discrete free-fall energy error| / energy drop, half-way",
          value = math.abs(mid.W_MPM - expected_w_mpm(mid)) / (m0 * g * 0.3), max = 1e-9 }
sim:save("outflow_mid.h5")
advance(150)
local d = sim:diagnostics()
T.check(sim:particle_count() == 0, "%d particles left in the grid at the end, expected 0", sim:particle_count())
T.check(d.outflow_particles == n0, "%d particles deleted, expected %d", d.outflow_particles, n0)
T.close(d.outflow_mass, m0, 1e-12, "outflow mass at the end")
local drop = m0 * g * 0.3 -- the block's potential energy drop to leaving, as a scale
T.expect{ id = "outflow.w_mpm_end", what = "|W_MPM - discrete free-fall energy error| / energy drop, whole block left",
          value = math.abs(d.W_MPM - expected_w_mpm(d)) / drop, max = 1e-9 }

-- the checkpoint keeps the policy and the book
local loaded = mpm.load("outflow_mid.h5", { thermo = 0, diagnostics = false })
local l0 = loaded:diagnostics()
T.check(l0.outflow_particles == mid.outflow_particles, "loaded outflow count %d, saved %d", l0.outflow_particles,
        mid.outflow_particles)
T.check(l0.energy_outflow == mid.energy_outflow, "loaded energy outflow %.17g, saved %.17g", l0.energy_outflow,
        mid.energy_outflow)
loaded:run{ steps = d.step - mid.step } -- to the step the straight run emptied at
local l = loaded:diagnostics()
T.check(l.outflow_particles == n0 and l.W_MPM == d.W_MPM,
        "loaded run: %d deleted, W_MPM %.17g; straight run: %d, %.17g", l.outflow_particles, l.W_MPM, n0, d.W_MPM)
T.done("outflow")
