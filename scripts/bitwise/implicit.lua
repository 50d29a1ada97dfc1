-- The implicit integrator (001): two elasto-plastic cylinders colliding,
-- FLIP, fixed dt, a checkpoint every 4 steps.
local out = mpm.param("out", ".")
local mat = mpm.material.von_mises{ density = 5, E = 100, nu = 0.3, yield = math.sqrt(1.5) * 10, hardening = 20 }
local colliding_cylinders = dofile(mpm.param("decks", "tests/decks") .. "/colliding_cylinders.lua")
local sim = colliding_cylinders(mat)
local imp = sim:implicit{ dt = 0.25, mapping = "FLIP", min_node_mass = 1e-3 }
for k = 1, 4 do
  for _ = 1, 4 do imp:step() end
  sim:save(string.format("%s/implicit_%d.h5", out, k))
end
