-- A 3D elastic cube (APIC, USL, quadratic B-splines) dropped onto a slip
-- floor, a checkpoint every 100 steps.
local out = mpm.param("out", ".")
local mat = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }
local sim = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 2.0 }, cell = 0.1 }, gravity = { 0.5, 0, -9.81 },
  scheme = { transfer = "APIC", stress_update = "USL" }, dt = { a_tau = 0.1 },
  boundary = { all = "slip", top = "free" }, thermo = 0, diagnostics = false }
sim:add_particles(mpm.box{ min = { 0.2, 0.2, 0.6 }, max = { 0.7, 0.7, 1.1 } }, { material = mat, per_axis = 2 })
for k = 1, 4 do
  sim:run{ steps = 100 }
  sim:save(string.format("%s/usl_apic_3d_%d.h5", out, k))
end
