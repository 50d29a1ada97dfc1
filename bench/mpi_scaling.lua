-- The problems bench/mpi.sh times on 1 and 2 processes (doc/performance.md,
-- "Distributed runs"): --set problem=a160k | c32 | collapse3d, steps=N.
--   a160k       bench.c's a160k: a 2D elastic column 1 m x 1 m on the floor
--               of a 6 m x 1.04 m grid, 1 cm cells, 4 x 4 particles per cell,
--               quadratic B-spline, APIC, USL, slip faces, dt = 0.05 h sqrt(rho / E)
--   c32         bench.c's c32: a 3D elastic cube of 32^3 cells of 0.1 m, 2 x 2 x 2
--               particles per cell, quadratic B-spline, APIC, USL
--   collapse3d  a 3D Mohr-Coulomb column 1 m x 0.5 m x 1 m collapsing on a
--               friction floor, 2.5 cm cells, 8 particles per cell (256,000),
--               cubic B-spline, FLIP, USF: the mass moves down and sideways,
--               so the slabs are re-cut (every 20 steps at 10 % imbalance)
-- Prints one line from process 0: particle-steps per second over the timed
-- steps (after 3 warm-up steps), and the bytes process 0 sent per step.
local problem = mpm.param("problem", "a160k")
local steps = mpm.param("steps", 40)
local rho, E, nu = 1748, 12.84e6, 0.16
local elastic = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }
local sim
if problem == "a160k" then
  local h = 0.01
  sim = mpm.simulation{ dim = 2, grid = { size = { 6, 1.04 }, cell = h }, shape = "quadratic_bspline",
    scheme = { transfer = "APIC", stress_update = "USL" }, gravity = { 0, -9.81 }, boundary = { all = "slip" },
    dt = { fixed = 0.05 * h * math.sqrt(rho / E) }, thermo = 0, diagnostics = false, watchdog = false }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 1, 1 } }, { material = elastic, per_axis = 4 })
elseif problem == "c32" then
  local h = 0.1
  sim = mpm.simulation{ dim = 3, grid = { size = { 3.6, 3.6, 3.6 }, cell = h }, shape = "quadratic_bspline",
    scheme = { transfer = "APIC", stress_update = "USL" }, gravity = { 0, -9.81, 0 }, boundary = { all = "slip" },
    dt = { fixed = 0.05 * h * math.sqrt(rho / E) }, thermo = 0, diagnostics = false, watchdog = false }
  sim:add_particles(mpm.box{ min = { 0.2, 0, 0.2 }, max = { 3.4, 3.2, 3.4 } }, { material = elastic, per_axis = 2 })
elseif problem == "collapse3d" then
  local sand = mpm.material.mohr_coulomb{ density = rho, E = E, nu = nu, phi = 33.75, psi = 0, cohesion = 1 }
  sim = mpm.simulation{ dim = 3, grid = { size = { 3, 0.5, 1.1 }, cell = 0.025 }, shape = "cubic_bspline",
    scheme = { transfer = "FLIP", stress_update = "USF" }, gravity = { 0, 0, -9.81 },
    boundary = { all = "slip", bottom = { "friction", mu = 0.3 }, top = "free" },
    dt = { cfl = 0.5 }, thermo = 0, diagnostics = false, watchdog = false }
  sim:add_particles(mpm.box{ min = { 0, 0, 0 }, max = { 1, 0.5, 1 } }, { material = sand, per_axis = 2 })
  sim:set_parallel{ rebalance_every = 20, imbalance = 1.1 }
else
  error("problem must be a160k, c32 or collapse3d, got " .. tostring(problem))
end
sim:run{ steps = 3 }
local p0 = sim:parallel()
local t0 = mpm.wall_time()
sim:run{ steps = steps }
local wall = mpm.wall_time() - t0
local p1 = sim:parallel()
local n = sim:diagnostics().particles
local halo = ((p1.halo_bytes or 0) - (p0.halo_bytes or 0)) / steps
local moved = ((p1.migrate_bytes or 0) - (p0.migrate_bytes or 0)) / steps
print(string.format("%s processes=%d threads=%s particles=%d steps=%d wall=%.4f rate=%.4g halo_bytes_per_step=%.0f " ..
                    "migrate_bytes_per_step=%.0f rebalances=%d", problem, p1.size, os.getenv("OMP_NUM_THREADS") or "?",
                    n, steps, wall, n * steps / wall, halo, moved, (p1.rebalances or 0) - (p0.rebalances or 0)))
