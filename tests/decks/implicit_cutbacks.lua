-- Cutbacks of the implicit step (`cutbacks`, doc/implicit.md#cutbacks): the
-- elasto-plastic colliding cylinders of 001 §7.3 (as tests/decks/
-- implicit_cylinders.lua, 16 points per cell, fixed dt = 0.5 s) with a Newton
-- limit `max_iter` below what some steps need.
--   cutbacks = 0: the run stops with the error naming the step and the
--     iteration limit;
--   cutbacks = 6: every step completes; at least one step was cut; every
--     accepted step converged within max_iter iterations; each step's dt is
--     0.5 s / 2^cuts; the time is the sum of the accepted steps; energy plus
--     plastic dissipation is constant to 1e-6 and linear momentum to
--     round-off, as without cuts (an abandoned attempt leaves nothing
--     behind);
--   the same through sim:run{ time = 8 } (hooks see each accepted step):
--     ends on time, steps cut as well, the energy balance of the run's own
--     accounts (W_MPM, 000 Eq. 68) below 1e-9 of the energy.
-- Parameters: max_iter (default 3), time (default 8 s).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local max_iter = mpm.param("max_iter", 3)
local tfinal = mpm.param("time", 8.0)
local dt = 0.5
local mat = mpm.material.von_mises{ density = 5, E = 100, nu = 0.3, yield = math.sqrt(1.5) * 10, hardening = 0 }

local colliding_cylinders = dofile(mpm.deck_dir .. "/colliding_cylinders.lua")
local function make() return colliding_cylinders(mat) end

local function run(cutbacks)
  local sim = make()
  local imp = sim:implicit{ dt = dt, max_iter = max_iter, cutbacks = cutbacks, min_node_mass = 1e-3 }
  local e0 = imp:energy()
  local pscale = 0
  for i = 1, sim:particle_count() do
    local v = sim:particle(i).v
    pscale = pscale + sim:particle(i).mass * math.sqrt(v[1] ^ 2 + v[2] ^ 2)
  end
  local s = { steps = 0, cut_steps = 0, cuts = 0, rejected = 0, iters = 0, time = 0, drift = 0, dp = 0, dt_error = 0 }
  while sim:time() < tfinal - 1e-12 do
    local ok, h = pcall(imp.step, imp)
    if not ok then
      s.error = h
      break
    end
    local e = imp:energy()
    s.steps = s.steps + 1
    s.iters = math.max(s.iters, h.iterations)
    if h.cuts > 0 then s.cut_steps = s.cut_steps + 1 end
    s.cuts, s.rejected = s.cuts + h.cuts, s.rejected + h.rejected_iterations
    s.dt_error = math.max(s.dt_error, math.abs(h.dt - dt / 2 ^ h.cuts) / dt)
    s.time = s.time + h.dt
    s.drift = math.max(s.drift, math.abs(e.total - e0.total) / e0.total)
    s.dp = math.max(s.dp, math.sqrt((e.momentum[1] - e0.momentum[1]) ^ 2 + (e.momentum[2] - e0.momentum[2]) ^ 2) / pscale)
  end
  s.sim_time, s.dissipated, s.e0 = sim:time(), imp:energy().dissipated, e0.total
  imp:free()
  sim:free()
  return s
end

local stop = run(0)
print(string.format("max_iter %d, no cutbacks: %d steps, then: %s", max_iter, stop.steps, tostring(stop.error)))
T.check(stop.error ~= nil, "max_iter = %d without cutbacks: the run did not stop (%d steps)", max_iter, stop.steps)
T.check(tostring(stop.error):find("did not converge in " .. max_iter .. " iterations", 1, true),
        "the error does not name the iteration limit: %s", tostring(stop.error))

local s = run(6)
print(string.format("max_iter %d, cutbacks 6: %d steps to %.4g s, %d steps cut (%d halvings, %d iterations rejected), "
                    .. "Newton <= %d, energy + dissipation constant to %.2e (dissipated %.4g of %.4g J/m), |dP| %.2e",
                    max_iter, s.steps, s.sim_time, s.cut_steps, s.cuts, s.rejected, s.iters, s.drift, s.dissipated,
                    s.e0, s.dp))
T.check(s.error == nil, "with cutbacks the run stopped: %s", tostring(s.error))
T.check(s.cut_steps > 0, "no step was cut back with max_iter = %d", max_iter)
T.check(s.dissipated > 0.01 * s.e0, "no plastic dissipation (%g)", s.dissipated)
T.expect{ id = "implicit_cutbacks.iterations", what = "most Newton iterations of an accepted step", value = s.iters,
          max = max_iter }
T.expect{ id = "implicit_cutbacks.cut_steps", what = "steps cut back", value = s.cut_steps }
T.expect{ id = "implicit_cutbacks.dt", what = "largest |dt - dt0 / 2^cuts| / dt0", value = s.dt_error, max = 1e-15 }
T.expect{ id = "implicit_cutbacks.time", what = "simulation time against the sum of the accepted steps (s)",
          value = s.sim_time, reference = s.time, rtol = 1e-12 }
T.expect{ id = "implicit_cutbacks.energy", what = "largest relative change of energy + plastic dissipation",
          value = s.drift, max = 1e-6 }
T.expect{ id = "implicit_cutbacks.momentum", what = "linear momentum change / sum m|v|", value = s.dp, max = 1e-10 }

-- the same driven by sim:run, which shortens the last step to end on time
local sim = make()
sim:implicit{ dt = dt, max_iter = max_iter, cutbacks = 6, min_node_mass = 1e-3 }
local run_cuts, run_steps = 0, 0
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() > 0 then
    run_steps, run_cuts = run_steps + 1, run_cuts + s:integrator():last().cuts
  end
end }
local E0 = sim:energy().total
sim:run{ time = tfinal }
local wmpm = sim:energy().mpm_error
print(string.format("sim:run: %d steps to %.6g s, %d halvings, W_MPM %.3e of %.4g J/m", run_steps, sim:time(), run_cuts,
                    wmpm, E0))
T.check(run_cuts > 0, "sim:run: no step was cut back")
T.expect{ id = "implicit_cutbacks.run_time", what = "sim:run end time (s)", value = sim:time(), reference = tfinal,
          rtol = 1e-12 }
T.expect{ id = "implicit_cutbacks.run_wmpm", what = "sim:run: |W_MPM| / initial energy", value = math.abs(wmpm) / E0,
          max = 1e-9 }
T.done("implicit_cutbacks")
