-- moraine robustness: violent runs that are right do not trip the watchdog.
-- The bouncing cube of 000 §4.1 through its first impact (PIC, which loses
-- most of its energy there, FLIP, which keeps it, and USL) and the dam break
-- of 002 §5.4 (cells = 10) until the surge has hit the far wall run with the
-- default bounds; each must end normally, and the largest ratios the watchdog
-- saw must stay well below its bounds (energy 1, dt 4, speed 1), by the
-- margins checked below.
local function check(ok, fmt, ...) if not ok then error(string.format(fmt, ...), 2) end end

local function report(label, sim)
  local w = sim:watchdog()
  print(string.format("%-22s checks %5d  W_MPM/E_scale %8.4f  dt/CFL %6.3f  cells/step %6.4f", label, w.checks,
                      w.energy, w.dt, w.speed))
  check(w.checks > 10, "%s: the watchdog checked %d times", label, w.checks)
  check(w.energy < 0.1, "%s: W_MPM reached %.3g of the energy scale", label, w.energy)
  check(w.dt < 1, "%s: dt reached %.3g times the CFL estimate", label, w.dt)
  check(w.speed < 0.5, "%s: a particle moved %.3g cells in a step", label, w.speed)
end

local cube = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }
for _, scheme in ipairs{ { "PIC", "USF" }, { "FLIP", "USF" }, { "FLIP", "USL" } } do
  local sim = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 2.6 }, cell = 0.2 }, gravity = { 0, 0, -9.81 },
    scheme = { transfer = scheme[1], stress_update = scheme[2] }, boundary = { all = "slip", top = "free" },
    dt = { a_tau = 0.05 }, thermo = 0, diagnostics = false, series = false }
  sim:add_particles(mpm.box{ min = { 0, 0, 1 }, max = { 1, 1, 2 } }, { material = cube, per_axis = 2 })
  sim:run{ time = 0.7 } -- the cube lands at 0.45 s
  report("cube " .. scheme[1] .. "/" .. scheme[2], sim)
end

local water = mpm.material.newtonian{ density = 1000, viscosity = 1.01e-3, sound_speed = 50 }
local dam = mpm.simulation{ dim = 2, grid = { size = { 4, 3 }, cell = 0.1 }, shape_boundary = "wls",
  scheme = { transfer = "APIC", stress_update = "USF" }, gravity = { 0, -9.81 }, boundary = { all = "slip" },
  dt = { cfl = 0.1 }, thermo = 0, diagnostics = false, series = false }
dam:add_particles(mpm.box{ min = { 0, 0 }, max = { 1, 2 } }, { material = water, per_axis = 2 })
dam:run{ time = 1.2 } -- the surge reaches the far wall near 0.7 s and climbs it
report("dam break APIC", dam)
