-- Sand column collapse (002 §5.5): a column of cohesionless sand, 1 m half-
-- width and 2 m high, against a symmetry wall, collapses under gravity onto
-- a rough floor and spreads until it stops. Drucker-Prager (phi = 35 deg,
-- psi = 0, c = 0, E = 10 MPa, nu = 0.3, rho = 1400 kg/m^3), TPIC with the WLS
-- kernel correction, Courant number 1. See README.md.
--
--   moraine examples/sand_column/deck.lua -o out/sand
--   moraine examples/sand_column/deck.lua -o out/sand --set cell=0.025
--
-- Parameters: cell (m; 0.05), height (m; 2), transfer (TPIC), shape (quadratic_bspline;
-- or gimp), floor (fixed; or slip), quick (false).
local quick = mpm.param("quick", false)
local g, L0 = 9.81, 1.0
local H0 = mpm.param("height", 2.0)
local presets = require "moraine.presets"
local sand_set = presets.parameters("sand_column") -- 002 §5.5: E = 10 MPa, nu = 0.3, phi = 35, c = 0, psi = 0, rho = 1400
local rho, nu = sand_set.density, sand_set.nu
local h = mpm.param("cell", quick and 0.1 or 0.05)
local W = 6.0
local tc = math.sqrt(H0 / g)

local sand = presets.material("sand_column") -- Drucker-Prager, 002 Eqs. 71-74
local sim = mpm.simulation{
  dim = 2,
  grid = { size = { W, H0 + 2 * h }, cell = h },
  shape = mpm.param("shape", "quadratic_bspline"),
  shape_boundary = "wls",
  scheme = { transfer = mpm.param("transfer", "TPIC"), stress_update = "USF" },
  gravity = { 0, -g },
  boundary = { left = "slip", right = "slip", bottom = mpm.param("floor", "fixed"), top = "free" },
  dt = { cfl = 1.0 },
  thermo = quick and 0 or 1000,
  output = { vtk = "sand", every = 0.05, fields = { "velocity", "displacement", "pressure", "eps_D", "stress" } },
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L0, H0 } }, { material = sand, per_axis = 2,
  stress = mpm.lithostatic{ density = rho, top = H0, K0 = nu / (1 - nu) } })
local Eg0 = sim:energy().gravity

-- the front (000 Eq. 70 uses the furthest particle) every 0.02 s
local function xmax(s)
  local x = 0
  for i = 1, s:particle_count() do x = math.max(x, s:particle(i).x[1]) end
  return x
end
os.execute("mkdir -p '" .. mpm.outdir .. "'")
local csv = assert(io.open(mpm.outdir .. "/front.csv", "w"))
csv:write("time,t_over_tc,front,L_x,runout_over_L0,E_kinetic\n")
sim:hook{ every_time = 0.02, fn = function(s)
  local x = xmax(s)
  local Lx = math.floor(x / h + 1) * h
  csv:write(string.format("%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", s:time(), s:time() / tc, x, Lx, (Lx - L0) / L0,
                          s:energy().kinetic))
end }
sim:run{ time = quick and 0.05 or 10 * tc,
         stop_when = function(s) return s:time() > 2 * tc and s:energy().kinetic < 1e-5 * Eg0 end }
csv:close()
sim:write_vtk()

-- the deposit: surface height in columns one cell wide
local top = {}
for i = 1, sim:particle_count() do
  local x = sim:particle(i).x
  local b = math.floor(x[1] / h)
  top[b] = math.max(top[b] or 0, x[2])
end
local dep = assert(io.open(mpm.outdir .. "/deposit.csv", "w"))
dep:write("x,height\n")
for b = 0, math.floor(W / h) - 1 do dep:write(string.format("%.6g,%.6g\n", (b + 0.5) * h, top[b] or 0)) end
dep:close()
local Lx = math.floor(xmax(sim) / h + 1) * h
print(string.format("sand column: t = %.3f s (%.2f t_c), E_kinetic = %.3g J/m; runout L_x = %.3f m, (L_x - L0)/L0 = %.3f",
                    sim:time(), sim:time() / tc, sim:energy().kinetic, Lx, (Lx - L0) / L0))
