-- Two elastic disks collide head-on and bounce apart (Sulsky, Chen and
-- Schreyer 1994): a unit square of 20 x 20 cells, disks of radius 0.2 m at
-- (0.2, 0.2) and (0.8, 0.8) moving towards each other at (0.1, 0.1) m/s,
-- E = 1000 Pa, nu = 0.3, rho = 1000 kg/m^3, dt = 1e-3 s. No gravity: the
-- total momentum stays zero to round-off.
--
--   moraine examples/colliding_disks/deck.lua -o out/disks
--   moraine examples/colliding_disks/deck.lua --set transfer=PIC --set time=2
local quick = mpm.param("quick", false)
local rubber = mpm.material.linear_elastic{ density = 1000, E = 1000, nu = 0.3, name = "disk" }

local sim = mpm.simulation{
  dim = 2,
  grid = { origin = { 0, 0 }, size = { 1, 1 }, cell = 0.05 },
  shape = "quadratic_bspline",
  scheme = { transfer = mpm.param("transfer", "FLIP"), stress_update = "USF" },
  boundary = { all = "slip" },
  dt = { fixed = 1e-3 },
  thermo = 500,
  output = { vtk = "disks", every = 0.05 },
}
sim:add_particles(mpm.disk{ center = { 0.2, 0.2 }, radius = 0.2 }, { material = rubber, velocity = { 0.1, 0.1 } })
sim:add_particles(mpm.disk{ center = { 0.8, 0.8 }, radius = 0.2 }, { material = rubber, velocity = { -0.1, -0.1 } })

sim:run{ time = quick and 0.2 or mpm.param("time", 3.5) }

local d = sim:diagnostics()
print(string.format("colliding disks: t = %.2f s, momentum (%.2e, %.2e) kg m/s per m, total energy %.6g J/m",
                    sim:time(), d.momentum[1], d.momentum[2], d.E_total))
