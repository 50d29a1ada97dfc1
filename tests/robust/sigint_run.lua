-- Run long enough to be interrupted: tests/robust/sigint.sh sends SIGINT once
-- the file "started" exists, and expects exit status 130 and a checkpoint
-- sig_interrupted.h5 in the output directory.
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, gravity = { 0, -9.81 },
  dt = { fixed = 1e-4 }, damping = { cundall = 0.05 }, thermo = 0, name = "sig",
  output = { vtk = "sig", every_steps = 5000 } }
sim:add_particles(mpm.disk{ center = { 0.5, 0.5 }, radius = 0.3 }, { material = mat,
  velocity = mpm.rigid_rotation{ omega = 1, center = { 0.5, 0.5 } } })
local flagged = false
sim:hook{ every_steps = 200, fn = function(s)
  if not flagged then
    local f = assert(io.open(mpm.outdir .. "/started", "w")) f:close()
    flagged = true
  end
end }
sim:run{ steps = mpm.param("steps", 400000) }
