-- After sigint.sh interrupted sigint_run.lua: load its checkpoint, finish the
-- same number of steps, and compare bitwise with an uninterrupted run.
local steps = mpm.param("steps", 400000)
local resumed = mpm.load("sig_interrupted.h5", { diagnostics = false, thermo = 0 })
local k = resumed:step()
assert(k > 0 and k < steps, "the interrupted run stopped at step " .. k)
resumed:run{ steps = steps - k }

local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local straight = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, gravity = { 0, -9.81 },
  dt = { fixed = 1e-4 }, damping = { cundall = 0.05 }, thermo = 0, diagnostics = false }
straight:add_particles(mpm.disk{ center = { 0.5, 0.5 }, radius = 0.3 }, { material = mat,
  velocity = mpm.rigid_rotation{ omega = 1, center = { 0.5, 0.5 } } })
straight:run{ steps = steps }
for _, f in ipairs{ "velocity", "displacement", "stress", "deformation_gradient" } do
  local a, b = resumed:field(f), straight:field(f)
  for i = 1, #a do
    if a[i] ~= b[i] then error(string.format("%s[%d] differs: %.17g vs %.17g", f, i, a[i], b[i])) end
  end
end
print(string.format("interrupted at step %d of %d; the resumed run matches the straight one bitwise", k, steps))
