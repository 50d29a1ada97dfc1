-- A run interrupted at a chosen step and continued with --restart
-- (tests/robust/resume.sh). Two run{} calls, so a restart in the second
-- skips the first; VTK snapshots on model time, CSV and series rows on
-- steps, a value recorded from a hook, periodic checkpoints in the second.
-- --set stop_at=K: at step K the deck writes OUTDIR/at_stop and waits (at
-- most 60 s of CPU) for the signal the test script then sends.
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, gravity = { 0, -9.81 },
  dt = { fixed = 1e-4 }, damping = { cundall = 0.05 }, thermo = 0, name = mpm.param("name", "block"),
  diagnostics_every = 7, output = { vtk = "block", every = 0.0013 } }
sim:add_particles(mpm.box{ min = { 0.3, 0.2 }, max = { 0.7, 0.6 } }, { material = mat,
  velocity = mpm.rigid_rotation{ omega = 1, center = { 0.5, 0.4 } } })
local stop_at = tonumber(mpm.param("stop_at", "-1"))
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() ~= stop_at then return end
  local f = assert(io.open(mpm.outdir .. "/at_stop", "w")) f:close()
  local t0 = os.clock()
  while os.clock() - t0 < 60 do end
end }
sim:hook{ every_steps = 10, fn = function(s) s:record("kinetic_x2", 2 * s:energy().kinetic) end }
sim:run{ time = 0.02 }
sim:run{ end_time = 0.05, checkpoint = { every = 50 } }
