-- A 2D granular column (Mohr-Coulomb, FLIP, USF, cubic B-splines) collapsing
-- onto a friction floor with a CFL time step, a checkpoint every 100 steps.
local out = mpm.param("out", ".")
local sand = mpm.material.mohr_coulomb{ density = 1748, E = 12.84e6, nu = 0.16, phi = 33.75, psi = 0, cohesion = 1 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 3.0, 1.2 }, cell = 0.05 }, gravity = { 0, -9.81 },
  shape = "cubic_bspline", shape_boundary = "modified", scheme = { transfer = "FLIP", stress_update = "USF" },
  dt = { cfl = 0.4 }, boundary = { all = "slip", top = "free", right = "free", bottom = { "friction", mu = 0.3 } },
  thermo = 0, diagnostics = false }
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.5, 1.0 } }, { material = sand, per_axis = 2 })
for k = 1, 5 do
  sim:run{ steps = 100 }
  sim:save(string.format("%s/usf_mc_flip_2d_%d.h5", out, k))
end
