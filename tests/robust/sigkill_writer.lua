-- Writes every kind of output file often and large, to be killed with
-- SIGKILL at a random moment (tests/robust/sigkill.sh): a 3D block of 32768
-- particles (a .vtp of 11 MB every step, with the grid as a .vti of 2 MB and
-- both .pvd rewritten each time), a CSV row, an HDF5 series row with a
-- recorded value and a 2 MB checkpoint every step: about half of the run's
-- wall time is spent writing.
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 1 }, cell = 0.03125 }, gravity = { 0, 0, -9.81 },
                            thermo = 0, progress = false, diagnostics = "diagnostics.csv", diagnostics_every = 1,
                            series = "series.h5", output = { vtk = "p", every_steps = 1, grid = true } }
sim:add_particles(mpm.box{ min = { 0.25, 0.25, 0.25 }, max = { 0.75, 0.75, 0.75 } }, { material = mat })
sim:particle_field{ name = "damage" }
sim:hook{ every_steps = 1, fn = function(s)
  s:record("com_z", s:reduce("mean", "z"))
  s:set_field("damage", s:time())
end }
sim:hook{ every_steps = 1, fn = function(s) s:save("checkpoint.h5") end }
local f = assert(io.open(mpm.outdir .. "/started", "w"))
f:close()
sim:run{ steps = 100000 }
