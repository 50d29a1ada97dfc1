-- The same deck on 1, 2 and 3 processes (tests/parallel/equivalence.py runs
-- it under mpirun and compares): --set case=collapse2d, a 2D FLIP/USF
-- Mohr-Coulomb column collapsing on a friction floor, or case=cube3d, a 3D
-- APIC/USL elastic cube, spinning, dropped on a slip floor with viscous
-- damping.
-- Writes the diagnostics every step (NAME.csv) and the final state
-- (NAME.h5, sim:save: every particle, in the order of their ids); the 2D
-- case also a VTK series every 250 steps (NAME.pvd, with grid snapshots in
-- NAME_grid.pvd), for ParaView's reader.
-- --set transfer=NAME replaces the case's strategy (XPIC(2): the smoothing's
-- extra passes, each with its halo sum); --set volumetric=fbar averages the
-- divergence over the nodes (its scatter with its halo sum); --set
-- rebalance=N re-cuts the slabs every N steps; --set late=N runs N steps,
-- then drops a second, moving block into the cube3d case (its initial affine
-- field found over every process's particles); --set load=FILE
-- continues from a checkpoint of either case instead (tests/parallel/restart.py).
local case = mpm.param("case", "collapse2d")
local steps = mpm.param("steps", 1000)
local name = mpm.param("name", case)
local rebalance = mpm.param("rebalance", 0)
local load = mpm.param("load", "")
local transfer = mpm.param("transfer", case == "cube3d" and "APIC" or "FLIP")
local volumetric = mpm.param("volumetric", "standard")
local late = mpm.param("late", 0)
local sim
if load ~= "" then
  sim = mpm.load(load, { thermo = 0, diagnostics = name .. ".csv" })
elseif case == "collapse2d" then
  local sand = mpm.material.mohr_coulomb{ density = 1748, E = 12.84e6, nu = 0.16, phi = 33.75, psi = 0, cohesion = 1 }
  sim = mpm.simulation{ dim = 2, grid = { size = { 3.0, 1.0 }, cell = 0.025 }, shape = "quadratic_bspline",
    scheme = { transfer = transfer, stress_update = "USF", volumetric = volumetric }, gravity = { 0, -9.81 },
    boundary = { left = "slip", right = "slip", bottom = { "friction", mu = 0.3 }, top = "free" },
    dt = { cfl = 0.5 }, thermo = 0, diagnostics = name .. ".csv", diagnostics_every = 1,
    output = { vtk = name, every_steps = 250, fields = { "velocity", "stress", "id" }, grid = true } }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.5, 0.8 } }, { material = sand, per_axis = 2 })
elseif case == "cube3d" then
  local rubber = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
  sim = mpm.simulation{ dim = 3, grid = { size = { 0.6, 0.6, 0.8 }, cell = 0.05 }, shape = "quadratic_bspline",
    scheme = { transfer = transfer, stress_update = "USL", volumetric = volumetric }, gravity = { 0, 0, -9.81 }, damping = { viscous = 0.5 },
    boundary = { left = "slip", right = "slip", front = "slip", back = "slip", bottom = "slip", top = "free" },
    dt = { cfl = 0.4 }, thermo = 0, diagnostics = name .. ".csv", diagnostics_every = 1 }
  sim:add_particles(mpm.box{ min = { 0.15, 0.15, 0.3 }, max = { 0.45, 0.45, 0.6 } },
                    { material = rubber, per_axis = 2, velocity = function(x, y, z)
                      -- falling, drifting and spinning at 2 rad/s about the cube's vertical axis
                      return 0.3 - 2 * (y - 0.3), -0.2 + 2 * (x - 0.3), -1.0
                    end })
else
  error("case must be collapse2d or cube3d, got " .. tostring(case))
end
if rebalance > 0 then sim:set_parallel{ rebalance_every = rebalance, imbalance = 1.0 } end
if late > 0 then
  if case ~= "cube3d" then error("late applies to case=cube3d") end
  sim:run{ steps = late }
  local rubber = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
  sim:add_particles(mpm.box{ min = { 0.2, 0.2, 0.64 }, max = { 0.4, 0.4, 0.74 } },
                    { material = rubber, per_axis = 2, velocity = function(x, y, z)
                      return 0.5 * (z - 0.69), -0.5, -1.5 + 3 * (x - 0.3)
                    end })
end
sim:run{ steps = steps - late }
sim:save(name .. ".h5")
local d = sim:diagnostics()
print(string.format("%s: %d steps, %d particles, E_total %.12g, W_MPM %.6g", name, sim:step(), d.particles, d.E_total,
                    d.W_MPM))
local par = sim:parallel()
if par.cuts then
  print(string.format("%d processes, slabs cut at cell rows %s along the last axis; %d re-cuts, %d particles sent, " ..
                      "%.3g MB of halo sums", par.size, table.concat(par.cuts, " "), par.rebalances, par.migrated,
                      par.halo_bytes / 1e6))
end
