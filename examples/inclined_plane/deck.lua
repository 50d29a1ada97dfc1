-- An elastic block slides down a rigid plane tilted by 30 degrees (gravity
-- vertical, the plane not aligned with the grid) with Coulomb friction
-- (mu = 0.3), and comes to rest against a rigid stopper further down. The
-- plane and the stopper are walls (sim:add_wall); their reaction forces go
-- to the HDF5 series from a hook, the friction work to W_friction.
--
--   moraine examples/inclined_plane/deck.lua -o out/incline
--   moraine examples/inclined_plane/deck.lua -o out/incline_steep --set theta=40
local quick = mpm.param("quick", false)
local theta = math.rad(mpm.param("theta", 30))
local mu = mpm.param("mu", 0.3)
local g = 9.81
local n = { math.sin(theta), math.cos(theta) } -- out of the plane
local t = { math.cos(theta), -math.sin(theta) } -- down the plane
local p = { 0.1, 1.6 }                          -- a point of the plane
local function at(s, h) return { p[1] + s * t[1] + h * n[1], p[2] + s * t[2] + h * n[2] } end

local sim = mpm.simulation{
  dim = 2,
  grid = { size = { 2.5, 2.0 }, cell = 0.025 },
  gravity = { 0, -g },
  scheme = "FLIP",
  boundary = { all = "slip", top = "free" },
  dt = { a_tau = 0.2 },
  thermo = 2000,
  output = { vtk = "block", every = 0.05 },
}
sim:add_wall{ name = "plane", shape = "plane", point = p, normal = n, kind = "friction", mu = mu }
-- the stopper: a post standing on the plane 1.2 m down from the block
sim:add_wall{ name = "stopper", shape = "polygon", kind = "slip",
              vertices = { at(1.8, -0.1), at(2.0, -0.1), at(2.0, 0.3), at(1.8, 0.3) } }
sim:add_particles(mpm.polygon{ vertices = { at(0.2, 0), at(0.6, 0), at(0.6, 0.2), at(0.2, 0.2) } },
                  { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }, per_cell = 4 })

sim:hook{ every_steps = 20, fn = function(s)
  local a, b = s:wall("plane"), s:wall("stopper")
  s:record("plane_fn", -(a.force[1] * n[1] + a.force[2] * n[2]))
  s:record("plane_ft", a.force[1] * t[1] + a.force[2] * t[2])
  s:record("stopper_ft", b.force[1] * t[1] + b.force[2] * t[2])
end }

local d0 = sim:diagnostics()
local t_slide = quick and 0.05 or 0.6
sim:run{ time = t_slide }
local d = sim:diagnostics()
local s = (d.center_of_mass[1] - d0.center_of_mass[1]) * t[1] + (d.center_of_mass[2] - d0.center_of_mass[2]) * t[2]
local a, exact = 2 * s / t_slide ^ 2, g * (math.sin(theta) - mu * math.cos(theta))
print(string.format("sliding: a = %.3f m/s^2, closed form g (sin theta - mu cos theta) = %.3f m/s^2", a, exact))
if not quick then
  sim:run{ time = mpm.param("time", 2.0) - t_slide }
  local e, w = sim:diagnostics(), sim:wall("stopper")
  local v = e.com_velocity[1] * t[1] + e.com_velocity[2] * t[2]
  print(string.format("after %.1f s: the block moves at %.3f m/s along the plane; the stopper took an impulse of %.1f N s/m",
                      sim:time(), v, w.impulse[1] * t[1] + w.impulse[2] * t[2]))
  print(string.format("W_friction = %.4g J/m, W_MPM = %.3g J/m", e.W_friction, e.W_MPM))
end
