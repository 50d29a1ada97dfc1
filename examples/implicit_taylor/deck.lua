-- Taylor bar impact with the implicit energy-momentum consistent integrator
-- (001 §7.4): a copper bar (K = 130 GPa, G = 43.3 GPa, rho = 8930 kg/m^3,
-- von Mises sigma_y = 0.4 GPa, linear hardening H = 0.1 GPa), radius 3.2 mm,
-- length 32.2 mm, hits a rigid frictionless wall at 227 m/s. Quarter model:
-- the symmetry planes x = 0, z = 0 and the wall y = 0 clamp the normal
-- velocity of the grid nodes on them; uGIMP, 0.8 mm cells, 2 points per cell
-- axis, dt = 0.375 us (001 Table 5). Prints each step's Newton history and
-- the energy balance; writes the particles at the end.
-- Known limit (doc/implicit.md): Newton stalls at about 35 us of the 80 us.
--
--   moraine examples/implicit_taylor/deck.lua -o out/taylor --set time=20e-6
local quick = mpm.param("quick", false)
local tend = mpm.param("time", quick and 0.3e-6 or 80e-6)
local K, G = 130e9, 43.3e9
local E, nu = 9 * K * G / (3 * K + G), (3 * K - 2 * G) / (2 * (3 * K + G))
local r0, h0, v0, h = 3.2e-3, 32.2e-3, 227.0, 0.8e-3
local copper = mpm.material.von_mises{ density = 8930, E = E, nu = nu, yield = 0.4e9, hardening = 0.1e9 }
local sim = mpm.simulation{ dim = 3, grid = { origin = { -2 * h, -2 * h, -2 * h }, size = { 11 * h, 45 * h, 11 * h }, cell = h },
                            shape = "gimp", thermo = 0, diagnostics = false, series = false,
                            output = { vtk = "taylor", every = 1 } }
local quarter = mpm.intersection(mpm.cylinder{ from = { 0, 0, 0 }, to = { 0, h0, 0 }, radius = r0 },
                                 mpm.box{ min = { 0, 0, 0 }, max = { r0, h0, r0 } })
sim:add_particles(quarter, { material = copper, per_axis = 2, velocity = { 0, -v0, 0 } })
local far = 1
sim:constrain{ region = mpm.box{ min = { -far, -far, -far }, max = { 1e-9, far, far } }, vx = 0 }
sim:constrain{ region = mpm.box{ min = { -far, -far, -far }, max = { far, far, 1e-9 } }, vz = 0 }
sim:constrain{ region = mpm.box{ min = { -far, -far, -far }, max = { far, 1e-9, far } }, vy = 0 }
local imp = sim:implicit{ mass = "consistent", mapping = "FLIP", tol = 1e-11, dt = 0.375e-6, max_iter = 30 }
local e0 = imp:energy()
print(string.format("%d points, initial kinetic energy %.4g J (quarter bar)", sim:particle_count(), e0.kinetic))
while sim:time() < tend - 1e-12 do
  local step = imp:step()
  local e = imp:energy()
  local errs = {}
  for k, v in ipairs(step.errors) do errs[k] = string.format("%.1e", v) end
  print(string.format("t = %.4e s  %2d iterations [%s]  dissipated %.4g J  energy change %.2e", sim:time(),
                      step.iterations, table.concat(errs, " "), e.dissipated, math.abs(e.total - e0.total) / e0.total))
end
sim:write_vtk()
