-- Contact between bodies survives --restart: two disks in frictional
-- contact (mu 0.2, FLIP), run 2.05 s (they move apart), saved, run 0.3 s
-- more; the contacts held at the save matter in the first step after it;
-- the last line holds a particle's position and velocity, W_contact and the
-- momentum to 17 digits (tests/robust/contact_restart.sh compares it with a
-- restarted run).
local rubber = mpm.material.linear_elastic{ density = 1000, E = 1000, nu = 0.3 }
local sim = mpm.simulation{ name = "disks", dim = 2, grid = { origin = { 0, 0 }, size = { 1, 1 }, cell = 0.05 },
                            shape = "quadratic_bspline", scheme = { transfer = "FLIP" }, boundary = { all = "free" },
                            dt = { fixed = 1e-3 }, thermo = 0, diagnostics = false }
sim:add_particles(mpm.disk{ center = { 0.2, 0.2 }, radius = 0.2 }, { material = rubber, velocity = { 0.1, 0.1 }, body = "a" })
sim:add_particles(mpm.disk{ center = { 0.8, 0.8 }, radius = 0.2 }, { material = rubber, velocity = { -0.1, -0.1 }, body = "b" })
sim:add_contact{ bodies = { "a", "b" }, kind = "friction", mu = 0.2 }
sim:run{ time = 2.05 }
sim:save(mpm.param("save", "mid.h5"))
sim:run{ time = 0.3 }
local p, d = sim:particle(100), sim:diagnostics()
print(string.format("state %.17g %.17g %.17g %.17g %.17g", p.x[1], p.v[1], d.W_contact, d.momentum[1], d.E_total))
