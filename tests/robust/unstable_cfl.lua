-- moraine robustness: a run with a time step 10 times the CFL estimate stops
-- at the first bad step with a message naming the particle and the step, and
-- leaves a readable final checkpoint (issue 8, must-show 4).
--
-- The same unstable run is made one step at a time: after every step that
-- passes, every particle field is checked finite here, in the deck. So when
-- the run stops at step N, the state at step N - 1 was entirely finite: the
-- guard stops the run at the very step the state goes bad (non-finite, an
-- inverted particle or one leaving the grid), not some steps later.
local mpm = require "moraine"
local function check(ok, fmt, ...) if not ok then error(string.format(fmt, ...), 2) end end

local mat = mpm.material.linear_elastic{ density = 1000, E = 1e8, nu = 0.3 }
local function make(name)
  local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, gravity = {0, -9.81}, thermo = 0,
    diagnostics = false, series = false, name = name, watchdog = false } -- the state check alone
  sim:add_particles(mpm.box{ min = {0.2, 0.0}, max = {0.6, 0.5} }, { material = mat,
    velocity = function(x, y) return 0, -5 * y end })
  local cfl = sim:dt_estimate().cfl -- h / max(c + |v|) (002, Eqs. 34-37)
  sim:set_dt{ fixed = 10 * cfl }
  return sim, cfl
end
mpm.warnings{ ignore = { "dt_above_cfl" } } -- the point of the test

-- 1. one run, as a deck would do it
local sim, cfl = make("unstable")
local ok, msg = pcall(sim.run, sim, { steps = 1000 })
check(not ok, "a run with dt = 10 x CFL did not stop")
check(math.abs(sim:dt() / cfl - 10) < 1e-12, "the run stepped with dt = %g, not 10 x %g", sim:dt(), cfl)
local step = tonumber(msg:match("run{}: step (%d+)"))
local particle = msg:match("particle (%d+)")
local saved_step, path = msg:match("the state at step (%d+) is in (%S+%.h5)")
check(step and particle and saved_step, "the message does not name the step, the particle and the checkpoint: %s", msg)
print(string.format("stopped at step %d (dt = 10 x %.3g s): %s", step, cfl, msg))

-- 2. the same, one step at a time, checking every field after each step
local fields = { "velocity", "displacement", "stress", "strain", "deformation_gradient", "volume", "mass" }
local function all_finite(s)
  for _, name in ipairs(fields) do
    for _, v in ipairs(s:field(name)) do
      if type(v) == "table" then
        for _, c in ipairs(v) do if c ~= c or c == math.huge or c == -math.huge then return false, name end end
      elseif v ~= v or v == math.huge or v == -math.huge then return false, name end
    end
  end
  return true
end
local again = make("stepwise")
local last_good = 0
for n = 1, 1000 do
  if not pcall(again.run, again, { steps = 1 }) then break end
  local finite, which = all_finite(again)
  check(finite, "after step %d the field %s holds a non-finite value the guard did not report", n, which)
  last_good = n
end
check(last_good + 1 == step, "the step-wise run stopped after step %d, the single run at step %d", last_good, step)
print(string.format("every field was finite up to step %d; the run stopped at step %d", last_good, step))

-- 3. the final checkpoint reads back: the last good state
local final = mpm.load(path)
check(final:step() == tonumber(saved_step) and final:step() >= step - 1,
      "the checkpoint holds step %d, the message said %s", final:step(), saved_step)
check(final:particle_count() == sim:particle_count(), "the checkpoint has %d particles, expected %d",
      final:particle_count(), sim:particle_count())
print(string.format("%s loads: %d particles at step %d", path, final:particle_count(), final:step()))
