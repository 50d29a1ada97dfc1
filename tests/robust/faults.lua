-- moraine robustness: a deck that writes every kind of output file, for the
-- fault injection of tests/robust/faults.py. In order: the provenance (before
-- the deck runs); a run writing particle (.vtp) and grid (.vti) snapshots
-- with their .pvd indexes, the diagnostics CSV and the HDF5 series (with a
-- value recorded from Lua); a checkpoint saved by the deck; a simulation
-- loaded from it, which a SIGINT stops after step 25 and which writes the
-- interrupted checkpoint. The first simulation is closed when the deck ends:
-- its CSV is synced and closed, and its series gets its last rewrite (a
-- column recorded after the checkpoint is still to be written). Without a
-- fault moraine exits with status 130.
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 0.5 }, cell = 0.05 }, gravity = { 0, -9.81 },
  thermo = 0, diagnostics_every = 2, output = { vtk = "part", every_steps = 5, grid = true } }
sim:add_particles(mpm.box{ min = { 0.1, 0.0 }, max = { 0.3, 0.2 } }, { material = mat })
sim:hook{ every_steps = 2, fn = function(s) s:record("top", s:reduce("max", "y")) end }
sim:run{ steps = 20 }
sim:save("state.h5")
sim:record("late", 1)

local resumed = mpm.load(mpm.outdir .. "/state.h5", { name = "resumed", thermo = 0, diagnostics = false })
-- Ctrl-C from a shell child (io.popen: os.execute's system() ignores SIGINT while it waits)
resumed:hook{ every_steps = 1, fn = function(s)
  if s:step() == 25 then io.popen("kill -INT $PPID"):close() end
end }
resumed:run{ steps = 20 }
