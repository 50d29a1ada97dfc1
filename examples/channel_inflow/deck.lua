-- A viscous jet through an inflow source: a Newtonian fluid (rho = 1000
-- kg/m^3, eta = 1 Pa s) enters an empty 2 m x 1 m box through a 0.2 m high
-- inlet in its left wall at 1 m/s, falls under gravity onto the slip floor
-- and leaves through the free right face, where on_leave = "delete" books
-- what goes out. The inflow ramps up over the first 0.2 s (a velocity
-- function of time). The mass in the box settles to a steady value once
-- the outflow matches the inflow, and the energy balance W_MPM closes with
-- the E_inflow, W_inflow and E_outflow columns of diagnostics.csv.
--
--   moraine examples/channel_inflow/deck.lua -o out/jet
local quick = mpm.param("quick", false)
local T = quick and 1.6 or mpm.param("time", 6.0)
local fluid = mpm.material.newtonian{ density = 1000, viscosity = 1.0, sound_speed = 20 }
local v = mpm.param("v", 1.0)

local sim = mpm.simulation{
  dim = 2,
  grid = { size = { 2, 1 }, cell = 0.04 },
  gravity = { 0, -9.81 },
  scheme = "APIC",
  boundary = { all = "slip", right = "free", top = "free" },
  on_leave = "delete",
  dt = { cfl = 0.4 },
  thermo = 500,
  output = { vtk = "jet", every = 0.1, fields = { "velocity", "pressure", "id" } },
}
-- the inlet: material enters through x = 0 between y = 0.6 and y = 0.8
sim:add_source{
  name = "inlet",
  region = mpm.box{ min = { 0, 0.6 }, max = { 0.08, 0.8 } },
  material = fluid,
  face = "xmin",
  velocity = function(t) return v * math.min(t / 0.2, 1), 0 end,
  per_axis = 2,
}

local rows = {}
sim:hook{ every_time = 0.5, fn = function(s)
  local d = s:diagnostics()
  rows[#rows + 1] = string.format("t = %4.1f s: mass in the box %7.2f kg/m, in %8.2f, out %8.2f, W_MPM / E_in %.2e",
    s:time(), d.mass, d.inflow_mass, d.outflow_mass, d.E_inflow > 0 and d.W_MPM / d.E_inflow or 0)
end }
sim:run{ time = T }
for _, r in ipairs(rows) do print(r) end
local src = sim:source("inlet")
-- the inflow ramps over 0.2 s: the material that has entered is rho A v (T - 0.1)
print(string.format("channel inflow: the source brought in %.4f kg/m; rho A v (T - 0.1) = %.4f kg/m", src.mass,
  src.density * src.area * v * (T - 0.1)))
