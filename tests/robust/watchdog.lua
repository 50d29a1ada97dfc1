-- moraine robustness: the watchdog stops an explosive run that the state
-- check cannot see (slip walls clamp the particles, every value stays
-- finite), with a checkpoint that loads; switched off, the same run ends
-- "normally" with W_MPM some 1e10 times its energy. Its options are checked
-- like every other key, and a driven boundary turns its energy test off.
local function check(ok, fmt, ...) if not ok then error(string.format(fmt, ...), 2) end end
mpm.warnings{ ignore = { "dt_above_cfl" } }

local mat = mpm.material.linear_elastic{ density = 1000, E = 1e15, nu = 0.3 }
local function explosive(name, watchdog)
  local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, gravity = {0, -9.81}, thermo = 0,
    boundary = { all = "slip" }, diagnostics = false, series = false, name = name, watchdog = watchdog }
  sim:add_particles(mpm.box{ min = {0, 0}, max = {0.4, 0.2} }, { material = mat })
  sim:set_dt{ fixed = 2300 * sim:dt_estimate().cfl }
  return sim
end

-- 1. off: the run ends with exit 0 and garbage (what the watchdog is for)
local off = explosive("off", false)
off:run{ steps = 50 }
local e = off:energy()
check(e.mpm_error > 1e9 * 78, "without the watchdog W_MPM reached only %g J", e.mpm_error)
print(string.format("watchdog off: 50 steps end normally with W_MPM = %.3g J", e.mpm_error))

-- 2. each test on its own stops it, with a checkpoint of the state it stopped on
for _, case in ipairs{ { "dt", { energy = 0, speed = 0 }, 1, "times the particle CFL estimate" },
                       { "energy", { dt = 0, speed = 0 }, 11, "the energy the discretisation created" } } do
  local label, opts, at, phrase = case[1], case[2], case[3], case[4]
  local sim = explosive("wd_" .. label, opts)
  local ok, msg = pcall(sim.run, sim, { steps = 300 })
  check(not ok and msg:find(phrase, 1, true), "%s test: the run did not stop as expected: %s", label, tostring(msg))
  check(sim:step() == at, "%s test: stopped at step %d, expected %d", label, sim:step(), at)
  local path = msg:match("the state at step %d+ is in (%S+%.h5)")
  check(path, "%s test: no checkpoint named: %s", label, msg)
  local saved = mpm.load(path)
  check(saved:step() == at and saved:particle_count() == sim:particle_count(),
        "%s test: the checkpoint holds step %d with %d particles", label, saved:step(), saved:particle_count())
  print(string.format("%-6s test: stopped at step %d; %s loads", label, at, path))
end

-- 3. its options are checked like any other key
for _, bad in ipairs{ { energy = -1 }, { dt = 0 / 0 }, { speed = math.huge * -1 }, { every = 0 }, { enrgy = 1 } } do
  local ok, msg = pcall(off.set_watchdog, off, bad)
  check(not ok and msg:find("set_watchdog() watchdog", 1, true), "set_watchdog accepted a bad value: %s",
        tostring(msg))
end
check(not pcall(mpm.simulation, { dim = 2, grid = { size = {1, 1}, cell = 0.1 }, watchdog = 3 }),
      "simulation{} accepted watchdog = 3")

-- 4. a moving velocity face does work W_MPM does not book: the energy test is off
local soft = mpm.material.linear_elastic{ density = 1000, E = 1e5, nu = 0.3 }
local driven = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, thermo = 0, diagnostics = false,
  series = false, boundary = { all = "slip", ymin = { "velocity", v = { 1, 0 } } }, dt = { cfl = 0.5 } }
driven:add_particles(mpm.box{ min = {0.2, 0}, max = {0.6, 0.2} }, { material = soft })
driven:run{ time = 0.2 }
local w = driven:watchdog()
check(w.checks > 0 and w.energy == 0, "driven run: %d checks, energy ratio %g (expected the test off)", w.checks,
      w.energy)
print(string.format("driven run: %d checks, W_MPM = %.3g J not tested", w.checks, driven:energy().mpm_error))
