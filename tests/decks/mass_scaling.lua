-- Mass scaling (simulation{ mass_scaling = f }): the particles' inertial mass
-- is f m, gravity acts on m.
--  1. the critical steps of sim:dt_estimate() grow by sqrt(f) (the particle
--     CFL, the grid CFL and a_tau), the viscous limit h^2 / nu by f;
--  2. a slow uniaxial compression (a velocity top face at 1 mm/s, 1 % strain
--     in 2 s, MUSL, cfl = 0.5) ends in the same mean vertical stress with f =
--     100 as with f = 1 within 1e-3, in sqrt(100) = 10 times fewer steps;
--  3. under gravity a settled column carries the weight of the true mass:
--     its mean vertical stress is the same with f = 100 as with f = 1 within
--     2 %, and -rho g H / 2 within 5 % (gravity is not scaled);
--  4. E_kinetic is 1/2 f m v^2: a block moving at v reports f times the
--     kinetic energy of its true mass.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local E, nu, rho = 1e6, 0.3, 1000
local mat = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }

local function block(f, extra)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 0.2, 0.2 }, cell = 0.02 }, mass_scaling = f,
    gravity = extra.gravity, boundary = extra.boundary, damping = extra.damping, thermo = 0, diagnostics = false,
    series = false, scheme = { transfer = "FLIP", stress_update = "MUSL" }, dt = { cfl = 0.5 } }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.2, extra.height or 0.2 } },
    { material = extra.material or mat, per_axis = 2, velocity = extra.velocity })
  return sim
end

-- 1. the critical steps
local plain, scaled = block(1, {}), block(100, {})
local e1, e100 = plain:dt_estimate(), scaled:dt_estimate()
for _, k in ipairs{ "cfl", "grid_cfl", "a_tau" } do
  T.close(e100[k] / e1[k], 10, 1e-12, "dt_estimate()." .. k .. " with mass_scaling = 100 over without")
end
local fluid = mpm.material.newtonian{ density = 1000, viscosity = 1e3, sound_speed = 1 }
local v1 = block(1, { material = fluid }):dt_estimate().cfl
local v4 = block(4, { material = fluid }):dt_estimate().cfl
T.close(v4 / v1, 4, 1e-12, "viscous limit h^2 / nu with mass_scaling = 4 over without")

-- 2. a slow compression: same stress, 10x fewer steps
local v = 1e-3
local function compress(f)
  local sim = block(f, { boundary = { all = "slip", top = { "velocity", v = { 0, -v } } } })
  sim:run{ time = 2 }
  return sim:reduce("mean", "stress", { component = 2 }), sim:step()
end
local s1, n1 = compress(1)
local s100, n100 = compress(100)
T.expect{ id = "mass_scaling.compression", what = "mean sigma_yy with mass_scaling = 100 / without",
          value = s100 / s1, reference = 1, rtol = 1e-3 }
T.close(n1 / n100, 10, 0.01, "steps without / with mass_scaling = 100")
local M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
T.close(s1, -M * 0.01, 0.05, "mean sigma_yy against M eps (the discretisation of the loaded face)")

-- 3. gravity acts on the true mass
local weight = {}
for _, f in ipairs{ 1, 100 } do
  local sim = block(f, { gravity = { 0, -9.81 }, damping = { cundall = 0.1 }, boundary = { all = "slip", top = "free" } })
  sim:run{ time = 1.0 * math.sqrt(f) } -- the settling is sqrt(f) slower
  weight[f] = sim:reduce("mean", "stress", { component = 2 })
  T.close(weight[f], -rho * 9.81 * 0.2 / 2, 0.05, "settled column, mass_scaling = " .. f .. ": mean sigma_yy")
end
T.expect{ id = "mass_scaling.weight", what = "settled column: mean sigma_yy with mass_scaling = 100 / without",
          value = weight[100] / weight[1], reference = 1, rtol = 0.02 }

-- 4. kinetic energy of the inertial mass
local moving = block(25, { velocity = { 0.1, 0 } })
local d = moving:diagnostics()
T.close(d.E_kinetic, 25 * 0.5 * d.mass * 0.01, 1e-12, "E_kinetic with mass_scaling = 25")
T.check(d.mass_scaling == 25, "diagnostics().mass_scaling = %s", tostring(d.mass_scaling))
T.done("mass_scaling")
