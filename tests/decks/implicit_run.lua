-- The implicit integrator driven by sim:run (src/implicit/implicit_run.c):
-- the colliding elastic cylinders of 001 §7.2 (as tests/decks/implicit_cylinders.lua,
-- 16 points per cell, FLIP, consistent mass) to t = 4.3 s.
--  1. sim:run{time} ends exactly on time: the last step is shortened;
--  2. the run gives bit for bit the particle state of the same steps made by
--     imp:step() in a deck loop (compared at the last full step);
--  3. the diagnostics see the implicit step's energy: W_MPM (000, Eq. 68)
--     stays within 1e-9 of the initial energy, and E_elastic equals
--     imp:energy().strain;
--  4. hooks, thermo-free CSV diagnostics and VTK output run as in explicit
--     runs: a hook every step reads imp:last() (Newton iterations, converged),
--     the VTK series has its snapshots;
--  5. a point force on one cylinder: its work W_external enters W_MPM, which
--     stays within 1e-9 of E_0 + |W_external|;
--  6. imp:free() hands sim:run back to the explicit step;
--  7. mpm.simulation{ integrator = "implicit", implicit = {...} } makes the
--     same integrator at the first run: bit for bit the state of sim:implicit{},
--     even when the deck keeps no reference to the integrator and the garbage
--     collector runs; sim:integrator() returns it.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local colliding_cylinders = dofile(mpm.deck_dir .. "/colliding_cylinders.lua")
local mat = mpm.material.hencky{ density = 5, E = 100, nu = 0.3 }
local t_end = 4.3

local function cylinders(output)
  local sim = colliding_cylinders(mat, { diagnostics = output and "diagnostics.csv" or false,
                                         output = output and { vtk = "cyl", every = 1.0 } or nil })
  local imp = sim:implicit{ mass = "consistent", mapping = "FLIP", tol = 1e-11, dt_factor = 1.15 }
  return sim, imp
end

-- the reference: a deck loop of imp:step()
local ref, ref_imp = cylinders(false)
local ref_times = {}
while ref:time() < t_end - 1e-12 do
  local dt = ref_imp:next_dt()
  if ref:time() + dt > t_end then break end
  ref_imp:step()
  ref_times[#ref_times + 1] = ref:time()
end

local sim, imp = cylinders(true)
local e0 = sim:energy().total
local steps, worst_final, most_iters = 0, 0, 0
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() == 0 then return end -- hooks also see the initial state
  local h = imp:last()
  steps = steps + 1
  most_iters = math.max(most_iters, h.iterations)
  if h.iterations > 0 then worst_final = math.max(worst_final, h.errors[h.iterations]) end -- 0: free flight, exact at once
  if steps == #ref_times then -- the last full step: compare with the deck loop
    T.check(s:time() == ref_times[#ref_times], "time %.17g differs from the loop's %.17g", s:time(), ref_times[#ref_times])
    local worst = 0
    for i = 1, s:particle_count() do
      local a, b = s:particle(i), ref:particle(i)
      for d = 1, 2 do worst = math.max(worst, math.abs(a.x[d] - b.x[d]), math.abs(a.v[d] - b.v[d])) end
    end
    T.check(worst == 0, "sim:run and the imp:step() loop differ by %.3g after %d steps", worst, steps)
  end
end }
sim:run{ time = t_end }
T.check(sim:time() == t_end, "sim:run ended at t = %.17g, expected %.17g", sim:time(), t_end)
T.check(steps == #ref_times + 1, "%d steps, expected the loop's %d and one shortened step", steps, #ref_times)
local e = sim:energy()
T.expect{ id = "implicit_run.W_MPM", what = "implicit run through sim:run: |W_MPM| / E_0", value = math.abs(e.mpm_error) / e0,
          max = 1e-9 }
T.close(e.elastic, imp:energy().strain, 1e-12, "E_elastic against the integrator's stored energy", 1e-15 * e0)
T.check(most_iters <= 6 and worst_final <= 1e-10, "Newton: %d iterations at most, final ratio %.3g", most_iters, worst_final)
local pvd = assert(io.open(mpm.outdir .. "/cyl.pvd")):read("a")
local _, snapshots = pvd:gsub("<DataSet ", "")
T.check(snapshots >= 5, "%d VTK snapshots, expected one a second and the start", snapshots)
print(string.format("implicit_run: %d steps to t = %g s, W_MPM %.3g of E_0, E_elastic %.6g, Newton <= %d iterations",
                    steps, sim:time(), math.abs(e.mpm_error) / e0, e.elastic, most_iters))

-- 5. a point force on the left cylinder
do
  local s2, i2 = cylinders(false)
  i2:point_force{ region = mpm.disk{ center = { 5.8, 5.5 }, radius = 2 }, force = { 0, 0.5 } }
  s2:run{ time = 2 }
  local e2 = s2:energy()
  -- the oblique impact pushes the lower, left cylinder down: the upward force's work may have either sign
  T.check(math.abs(e2.external) > 1e-6 * e0, "W_external %g should not vanish", e2.external)
  T.expect{ id = "implicit_run.W_MPM_loaded", what = "implicit run with a point force: |W_MPM| / (E_0 + |W_ext|)",
            value = math.abs(e2.mpm_error) / (e0 + math.abs(e2.external)), max = 1e-9 }
  -- 6. back to the explicit step
  i2:free()
  local before = s2:step()
  s2:run{ steps = 3 }
  T.check(s2:step() == before + 3, "explicit steps after imp:free()")
  print(string.format("implicit_run loaded: W_external %.6g J/m, W_MPM %.3g", e2.external, e2.mpm_error))
end

-- 7. the deck switch in mpm.simulation{}
do
  local opts = { mass = "consistent", mapping = "FLIP", tol = 1e-11, dt_factor = 1.15 }
  local function pair(switch)
    local s = mpm.simulation{ dim = 2, grid = { size = { 20, 12 }, cell = 2 }, shape = "linear", thermo = 0,
                              diagnostics = false, series = false,
                              integrator = switch and "implicit" or nil, implicit = switch and opts or nil }
    for _, c in ipairs{ { 5.8, 5.5, 0.75 }, { 14.2, 6.5, -0.75 } } do
      s:add_particles(mpm.disk{ center = { c[1], c[2] }, radius = 2 },
                      { material = mat, velocity = { c[3], 0 }, per_cell = 16, placement = "regular" })
    end
    if not switch then s:implicit(opts) end -- no reference kept: the simulation holds it
    return s
  end
  local a, b = pair(true), pair(false)
  local e0a = a:energy().total
  T.check(a:integrator() ~= nil and b:integrator() ~= nil, "sim:integrator() should return the implicit integrator")
  collectgarbage("collect")
  a:run{ time = 1.5 }
  b:run{ time = 1.5 }
  collectgarbage("collect")
  a:run{ time = 0.5 }
  b:run{ time = 0.5 }
  local worst = 0
  for i = 1, a:particle_count() do
    local pa, pb = a:particle(i), b:particle(i)
    for d = 1, 2 do worst = math.max(worst, math.abs(pa.x[d] - pb.x[d]), math.abs(pa.v[d] - pb.v[d])) end
  end
  T.check(worst == 0, "integrator = \"implicit\" and sim:implicit{} differ by %.3g", worst)
  T.check(a:integrator():last().iterations > 0, "the switch's integrator made Newton steps")
  local e = a:energy()
  T.expect{ id = "implicit_run.switch_W_MPM", what = "integrator = \"implicit\": |W_MPM| / E_0",
            value = math.abs(e.mpm_error) / e0a, max = 1e-9 }
  a:integrator():free()
  T.check(a:integrator() == nil, "sim:integrator() after imp:free() should be nil (explicit)")
end
T.done("implicit_run")
