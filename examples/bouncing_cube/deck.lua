-- The bouncing cube of 000 §4.1: a 1 m elastic cube falls 1 m onto the floor
-- of a 5 x 5 x 13 grid of 0.2 m cells and bounces. 8 particles per cell at
-- the Gauss-Legendre points, E = 12.84 MPa, nu = 0.16, rho = 1748 kg/m^3,
-- g = 9.81 m/s^2, slip walls, dt = a_tau l_cell sqrt(rho / E) with a_tau = 0.05.
-- FLIP keeps the total energy (about 25.7 kJ); PIC loses most of it at the
-- first impact (000 Fig. 3).
--
-- The run draws energies.png (energies against time) and momentum.png
-- (vertical momentum) from its diagnostics CSV with moraine-plot
-- (lua/moraine/plot.lua); --set plot=false skips them (default: true, false
-- in quick runs unless --set plot=true).
--
--   moraine examples/bouncing_cube/deck.lua -o out/cube --set transfer=PIC
local plot = require "moraine.plot"
local quick = mpm.param("quick", false)
local draw = mpm.param("plot", not quick)
local transfer = mpm.param("transfer", "FLIP")
local cube_material = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }

local sim = mpm.simulation{
  dim = 3,
  grid = { size = { 1, 1, 2.6 }, cell = 0.2 },
  gravity = { 0, 0, -9.81 },
  scheme = { transfer = transfer, stress_update = mpm.param("stress_update", "USF") },
  boundary = { all = "slip", top = "free" },
  dt = { a_tau = mpm.param("a_tau", 0.05) },
  thermo = 1000,
  diagnostics_every = 10,
  output = { vtk = "cube_" .. transfer, every = 0.02 },
}
sim:add_particles(mpm.box{ min = { 0, 0, 1 }, max = { 1, 1, 2 } }, { material = cube_material, per_axis = 2 })

local e0 = sim:energy().total
sim:run{ time = quick and 0.1 or mpm.param("time", 2.0) }
local e = sim:energy().total
print(string.format("bouncing cube (%s): total energy %.5g J -> %.5g J (%.2f %%)", transfer, e0, e,
                    100 * (e - e0) / e0))

if draw then
  local ok, err = plot.series{ png = "energies.png", file = "diagnostics.csv",
                               columns = { "E_kinetic", "E_gravity", "E_elastic", "E_total" },
                               title = "Bouncing cube (" .. transfer .. "): energies", ylabel = "energy (J)" }
  if ok then
    ok, err = plot.series{ png = "momentum.png", file = "diagnostics.csv", columns = { "momentum_z" },
                           title = "Bouncing cube (" .. transfer .. "): vertical momentum", ylabel = "momentum (kg m/s)" }
  end
  print(ok and "plots: energies.png momentum.png" or err)
end
