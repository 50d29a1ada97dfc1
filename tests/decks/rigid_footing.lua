-- A rigid footing settling under its own weight on an elastic layer, 2D.
--
-- The layer (H = 1 m, E = 10 MPa, nu = 0.3, rho = 2000 kg/m^3, seeded with
-- its geostatic stress, sigma_xx = nu / (1 - nu) sigma_yy) fills the grid's
-- width (0.1 m) between slip side faces on a slip base: one-dimensional
-- confined compression. A box body spanning the whole width, of mass
-- M = p A / g (p = 50 kPa, A = 0.1 m per metre of depth), fixed in x and rz,
-- is released resting on it and brought to rest in 2 s by either damping:
-- Cundall's, D = 0.3 (on the soil's nodes and the footing's own net force),
-- or mass-proportional, alpha = 100 1/s (near critical for the
-- footing-on-layer mode). Cells of 0.025 m (40 over H), 4 points per cell,
-- APIC, dt = 0.3 a_tau. Asserted for each: the settlement against
-- delta = (W / A) H / (lambda + 2 G) within 5 % (the discrete column is
-- about one cell softer: 3.1 % and 3.0 % here, 4.9 % with 20 cells over H),
-- the resting reaction against the weight M g within 1 % (0.4 %), the
-- footing at rest (|v| < 1e-2 delta / s), and W_MPM below 2 % of the work
-- of gravity on the footing (0.3 %, 0.8 %).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local g, rho, E, nu = 9.81, 2000, 10e6, 0.3
local A, H, cell, p = 0.1, 1.0, tonumber(mpm.param("cell", "0.025")), 50e3
local M = p * A / g
local lambda2G = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
local delta = p * H / lambda2G
local k0 = nu / (1 - nu)
local function geostatic(_, y)
  local s = -rho * g * (H - y)
  return { k0 * s, s, nu * (k0 + 1) * s, 0, 0, 0 }
end

local function footing(name, damping)
  local sim = mpm.simulation{ dim = 2, grid = { size = { A, 1.5 }, cell = cell }, shape = "quadratic_bspline",
                              scheme = "APIC", gravity = { 0, -g }, boundary = { all = "slip", top = "free" },
                              dt = { a_tau = 0.3 }, damping = damping, diagnostics = false, thermo = 0,
                              progress = false }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { A, H } },
                    { material = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }, per_cell = 4,
                      stress = geostatic })
  sim:add_wall{ name = "footing", shape = "box", min = { -2 * cell, H }, max = { A + 2 * cell, H + 0.2 }, mass = M,
                fix = { "x", "rz" } }
  local y0 = sim:wall("footing").pivot[2]
  sim:run{ time = tonumber(mpm.param("time", "2")) }
  local w, d = sim:wall("footing"), sim:diagnostics()
  local id = "rigid_footing." .. name
  T.expect{ id = id .. ".settlement", what = name .. ": settlement against (W/A) H / (lambda + 2 G)",
            value = y0 - w.pivot[2], reference = delta, rtol = 0.05, unit = "m" }
  T.expect{ id = id .. ".reaction", what = name .. ": resting reaction against the weight", value = w.force[2],
            reference = M * g, rtol = 0.01, unit = "N/m" }
  T.check(math.abs(w.velocity[2]) < 1e-2 * delta, "%s: the footing is not at rest: v = %g m/s", name, w.velocity[2])
  T.check(w.velocity[1] == 0 and w.omega == 0, "%s: the footing moved along a fixed degree of freedom", name)
  T.expect{ id = id .. ".w_mpm", what = name .. ": |W_MPM| / W_bodies", value = math.abs(d.W_MPM) / d.W_bodies,
            max = 0.02 }
end

footing("cundall", { cundall = 0.3 })
footing("viscous", { viscous = 100 })
T.done("rigid_footing")
