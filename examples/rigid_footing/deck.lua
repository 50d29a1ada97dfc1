-- A rigid strip footing released onto a Mohr-Coulomb soil layer (2D, plane
-- strain). The footing is a rigid body (sim:add_wall with a density): it
-- sinks under its own weight and a building load (external_force) until
-- the soil carries it, held against sliding and tilting (fix = {"x", "rz"}).
-- The soil starts from its geostatic stress; viscous damping brings the
-- system to rest. Printed: the settlement, the footing's reaction against
-- its weight plus the load, and the energy balance with the body's terms.
--
--   moraine examples/rigid_footing/deck.lua -o out/footing
--   moraine examples/rigid_footing/deck.lua -o out/footing_heavy --set q=250e3
--   moraine examples/rigid_footing/deck.lua -o out/footing_free --set free=true
local quick = mpm.param("quick", false)
local g = 9.81
local B, t_f, rho_f = 1.0, 0.5, 2400        -- footing width, height (m), concrete density
local q = mpm.param("q", 100e3)              -- the building load per unit area (Pa)
local L, H = 6.0, 3.0                        -- soil layer (m)
local rho, E, nu, phi, c = 1800, 20e6, 0.3, 30, 10e3
local cell = quick and 0.2 or 0.1

local sim = mpm.simulation{
  dim = 2,
  grid = { size = { L, H + 1.0 }, cell = cell },
  gravity = { 0, -g },
  scheme = "APIC",
  boundary = { all = "slip", top = "free" },
  dt = { a_tau = 0.3 },
  damping = { viscous = 20 },
  thermo = quick and 0 or 2000,
  output = { vtk = not quick and "footing" or nil, every = 0.1 },
}
local k0 = nu / (1 - nu)
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L, H } }, {
  material = mpm.material.mohr_coulomb{ density = rho, E = E, nu = nu, phi = phi, psi = 0, cohesion = c },
  per_cell = 4,
  stress = function(_, y)
    local s = -rho * g * (H - y)
    return { k0 * s, s, nu * (1 + k0) * s, 0, 0, 0 }
  end,
})
sim:add_wall{ name = "footing", shape = "box", min = { 0.5 * (L - B), H }, max = { 0.5 * (L + B), H + t_f },
              kind = "friction", mu = 0.5, density = rho_f, external_force = { 0, -q * B },
              fix = not mpm.param("free", false) and { "x", "rz" } or nil }
sim:hook{ every_steps = 200, fn = function(s)
  local w = s:wall("footing")
  s:record("settlement", H + 0.5 * t_f - w.pivot[2])
  s:record("reaction_y", w.force[2])
end }
local w0 = sim:wall("footing")
local weight = w0.mass * g + q * B
sim:run{ time = quick and 0.3 or 2.0 }
local w, d = sim:wall("footing"), sim:diagnostics()
-- the elastic settlement of a rigid strip on a half-space is not finite; as a
-- scale, the 1D confined compression of the layer under the footing's pressure
local lambda2G = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
print(string.format("footing: mass %.0f kg/m, weight + load %.0f N/m (%.0f kPa)", w.mass, weight, weight / B / 1e3))
print(string.format("settlement %.2f mm (1D confined scale (W/B) H / (lambda + 2G) = %.2f mm), velocity %.2e m/s",
                    1e3 * (H + 0.5 * t_f - w.pivot[2]), 1e3 * weight / B * H / lambda2G, w.velocity[2]))
print(string.format("reaction %.0f N/m = %.4f of weight + load", w.force[2], w.force[2] / weight))
print(string.format("E_bodies %.3g J/m, W_bodies %.4g J/m, W_plastic %.4g J/m, W_damping %.4g J/m, W_MPM %.3g J/m",
                    d.E_bodies, d.W_bodies, d.W_plastic, d.W_damping, d.W_MPM))
