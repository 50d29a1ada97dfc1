-- An inflow source continued with --restart (tests/robust/source_restart.sh):
-- a channel fed by a ramped inflow (a velocity function), the outflow deleted,
-- particles reordered every 25 steps; periodic checkpoints every 200 steps.
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 0.6, 0.2 }, cell = 0.02 }, name = "channel",
  boundary = { all = "slip", right = "free" }, on_leave = "delete", thermo = 0, sort_every = 25,
  scheme = "APIC", dt = { cfl = 0.4 } }
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.2, 0.2 } }, { material = mat, per_axis = 2, placement = "regular" })
sim:add_source{ name = "inlet", region = mpm.box{ min = { 0, 0 }, max = { 0.06, 0.2 } }, material = mat, face = "xmin",
  velocity = function(t) return 0.5 * math.min(t / 0.05, 1), 0 end }
sim:run{ steps = 600, checkpoint = { every = 200, keep = 0 } }
