-- Dam break (002 §5.4): a water column 1 m wide and 2 m high collapses in a
-- 4 m x 3 m tank with free-slip walls, runs along the floor, hits the far
-- wall and climbs it. Newtonian fluid with Morris's equation of state
-- (mu = 1.01e-3 Pa s, c = 50 m/s, rho_ref = 1000 kg/m^3), APIC with the WLS
-- kernel correction, Courant number 0.1. See README.md.
--
--   moraine examples/dam_break/deck.lua -o out/dam_break
--   moraine examples/dam_break/deck.lua -o out/dam_break --set cells=40 --set transfer=TPIC
--
-- Parameters: cells (cells across the column width a; 20), transfer (APIC), shape
-- (quadratic_bspline; or gimp), time (s; 1.5), quick (false).
local quick = mpm.param("quick", false)
local a, g = 1.0, 9.81
local h = a / mpm.param("cells", quick and 10 or 20)
local scale = math.sqrt(2 * g / a) -- Martin & Moyce's T = t sqrt(2 g / a)

local water = mpm.material.newtonian{ density = 1000, viscosity = 1.01e-3, sound_speed = 50 } -- 002 Eqs. 69-70
local sim = mpm.simulation{
  dim = 2,
  grid = { size = { 4 * a, 3 * a }, cell = h },
  shape = mpm.param("shape", "quadratic_bspline"),
  shape_boundary = "wls",
  scheme = { transfer = mpm.param("transfer", "APIC"), stress_update = "USF" },
  gravity = { 0, -g },
  boundary = { all = "slip" },
  dt = { cfl = 0.1 },
  thermo = quick and 0 or 2000,
  output = { vtk = "water", every = 0.05, fields = { "velocity", "pressure", "density" } },
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { a, 2 * a } }, { material = water, per_axis = 2 })

-- surge front from a hook: largest particle x plus the gap from the outermost
-- Gauss point to its cell face, so that Z = 1 at the start
local gap = (1 - 1 / math.sqrt(3)) * h / 2
os.execute("mkdir -p '" .. mpm.outdir .. "'")
local csv = assert(io.open(mpm.outdir .. "/front.csv", "w"))
csv:write("time,T,Z\n")
sim:hook{ every_time = 0.01, fn = function(s)
  local x = 0
  for i = 1, s:particle_count() do x = math.max(x, s:particle(i).x[1]) end
  csv:write(string.format("%.6g,%.6g,%.6g\n", s:time(), s:time() * scale, (x + gap) / a))
end }
sim:run{ time = quick and 0.05 or mpm.param("time", 1.5) }
csv:close()

-- Martin & Moyce (1952), n^2 = 2 (VALIDATION.md), for the plot
local mm = assert(io.open(mpm.outdir .. "/martin_moyce.csv", "w"))
mm:write("T,Z\n")
local T_mm = { 0.41, 0.84, 1.19, 1.43, 1.63, 1.83, 1.98, 2.20, 2.32, 2.51 }
local Z_mm = { 1.11, 1.22, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56, 2.78, 3.00 }
for k = 1, #T_mm do mm:write(string.format("%g,%g\n", T_mm[k], Z_mm[k])) end
mm:close()
local d = sim:diagnostics()
print(string.format("dam break: t = %.3f s (T = %.2f), %d steps, E_kinetic = %.4g J/m, W_MPM = %.4g J/m",
                    sim:time(), sim:time() * scale, sim:step(), d.E_kinetic, d.W_MPM))
