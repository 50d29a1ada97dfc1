-- Distributed runs that go wrong, or nearly (tests/parallel/robust.sh):
--   case=crossing    one block of particles, thin slabs: it starts on process 0 with
--                    the others empty, and in one step crosses process 1's slab into
--                    process 2's; mass, momentum and the free-flight position hold
--   case=lua_error   a hook raises an error on the last process only, at step 20
--   case=leave       the same block's second step carries it out of the grid: every
--                    process stops with the diagnosis and one checkpoint is written
--   case=outflow     as leave with on_leave = "delete": the block is deleted on the
--                    process that holds it, and every process books its energy as outflow
--   case=small_grid  8 cells along y for 3 processes (4 each at least)
--   case=cpdi_thin   a CPDI bar stretching along y on 3 slabs of 4 cells: its
--                    domains come to reach a cell from their particles (the
--                    shape functions two), which takes bands of 5 node rows and
--                    slabs of 5 cells between two
--   case=sigint      a long run that the driver interrupts (SIGINT to mpirun)
--   case=vtk_resume  a VTK snapshot every 10 steps and a checkpoint every 15, for 40 steps:
--                    robust.sh continues it from its first checkpoint on another process count
local case = mpm.param("case", "crossing")
local steel = mpm.material.linear_elastic{ density = 7800, E = 2e8, nu = 0.3 }
local function check(ok, fmt, ...)
  if not ok then error(string.format(fmt, ...), 2) end
end

if case == "crossing" or case == "leave" or case == "outflow" then
  -- 12 cells of 0.1 m along y on 3 processes: slabs of 4 cells; no gravity, no
  -- stress (a rigid translation), one step of 0.01 s at 100 m/s carries the
  -- block 1 m = 10 cells up, from process 0's slab over process 1's into 2's
  -- (ten cells a step: the watchdog, which would stop that, is off, and so is
  -- the warning that dt is above the CFL estimate)
  mpm.warnings{ ignore = { "dt_above_cfl" } }
  local sim = mpm.simulation{ dim = 2, grid = { size = { 0.4, 1.2 }, cell = 0.1 }, gravity = { 0, 0 },
    scheme = { transfer = "PIC", stress_update = "USL" }, dt = { fixed = 0.01 }, thermo = 0, watchdog = false,
    boundary = { all = "free" }, diagnostics = "crossing.csv", diagnostics_every = 1, name = case,
    on_leave = case == "outflow" and "delete" or "stop",
    -- a snapshot a step, pieces of empty processes among them (robust.sh reads them); the leave
    -- case's gathered into one .vtp each
    output = { vtk = case, every_steps = 1, fields = { "velocity", "stress", "id" }, grid = true,
               gather = case == "leave" } }
  sim:add_particles(mpm.box{ min = { 0.1, 0.05 }, max = { 0.3, 0.15 } },
                    { material = steel, per_axis = 2, velocity = { 0, 100 } })
  local d0 = sim:diagnostics()
  sim:run{ steps = case == "crossing" and 1 or 2 }
  local d, par = sim:diagnostics(), sim:parallel()
  if case == "outflow" then
    check(d.particles == 0, "%d particles left after the block went out", d.particles)
    check(math.abs(d.E_outflow - d0.E_kinetic) <= 1e-12 * d0.E_kinetic, "E_outflow %.17g, the block had E_k %.17g",
          d.E_outflow, d0.E_kinetic)
    check(math.abs(d.W_MPM) <= 1e-9 * d0.E_kinetic, "W_MPM %.3g after the outflow", d.W_MPM)
    -- the counts are the whole run's, whichever process deleted the particles
    check(d.outflow_particles == d0.particles, "outflow_particles %d, the block had %d", d.outflow_particles,
          d0.particles)
    check(math.abs(d.outflow_mass - d0.mass) <= 1e-12 * d0.mass, "outflow_mass %.17g, the block had %.17g",
          d.outflow_mass, d0.mass)
    print(string.format("outflow: the block's %.6g J/m left as E_outflow %.6g J/m on %d processes", d0.E_kinetic,
                        d.E_outflow, par.size))
    return
  end
  print(string.format("process %d of %d holds %d particles; cuts %s", par.rank, par.size, par.particles,
                      table.concat(par.cuts or {}, " ")))
  check(d.particles == d0.particles, "particles %d after the step, %d before", d.particles, d0.particles)
  check(math.abs(d.mass - d0.mass) <= 1e-12 * d0.mass, "mass %.17g, was %.17g", d.mass, d0.mass)
  check(math.abs(d.momentum_y - d0.momentum_y) <= 1e-12 * d0.momentum_y, "momentum_y %.17g, was %.17g",
        d.momentum_y, d0.momentum_y)
  check(math.abs(d.com_y - (0.1 + 1.0)) < 1e-9, "centre of mass at y = %.12g, expected 1.1", d.com_y)
  -- sim:reduce and sim:probe answer for every process: the block's mass, and
  -- the grid velocity of the step where it started, in process 0's slab
  -- (which holds no particle any more)
  local m = sim:reduce("sum", "mass")
  check(math.abs(m - d.mass) <= 1e-12 * d.mass and sim:reduce("count", "mass") == d.particles,
        "reduce: mass %.17g over %d particles, the diagnostics %.17g over %d", m, sim:reduce("count", "mass"),
        d.mass, d.particles)
  local vy = sim:probe{ field = "velocity_new", x = 0.2, y = 0.1 }[2]
  check(math.abs(vy - 100) < 1e-9, "probe: velocity_new y at (0.2, 0.1) is %.12g, expected 100", vy)
  -- sim:field{gather = true}: every particle in the order of the ids, on every process
  local ids = sim:field("id", { gather = true })
  local vel, nc = sim:field("velocity", { gather = true })
  check(#ids == d.particles and nc == 3 and #vel == 3 * d.particles, "gather: %d ids, %d velocities for %d particles",
        #ids, #vel // 3, d.particles)
  for i = 2, #ids do check(ids[i] > ids[i - 1], "gather: ids out of order at %d", i) end
  for i = 1, #ids do check(math.abs(vel[3 * i - 1] - 100) < 1e-9, "gather: v_y %.17g of id %d", vel[3 * i - 1], ids[i]) end
  -- every particle sits on the process whose slab holds it
  if par.size == 3 then
    check(par.particles == (par.rank == 2 and d0.particles or 0), "process %d holds %d particles", par.rank,
          par.particles)
  end
  sim:save("crossing.h5")
elseif case == "lua_error" or case == "sigint" then
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 1.0 }, cell = 0.05 }, gravity = { 0, -9.81 },
    scheme = { transfer = "FLIP", stress_update = "USF" }, dt = { cfl = 0.2 }, thermo = 0, name = case,
    boundary = { bottom = "slip" } }
  sim:add_particles(mpm.box{ min = { 0.2, 0 }, max = { 0.8, 0.9 } }, { material = steel, per_axis = 2 })
  if case == "lua_error" then
    sim:hook{ every_steps = 1, fn = function(s)
      local par = s:parallel()
      if s:step() == 20 and par.rank == par.size - 1 then error("the last process gives up at step 20") end
    end }
    sim:run{ steps = 100 }
  else
    sim:hook{ every_steps = 1, fn = function(s)
      if s:step() == 5 and s:parallel().rank == 0 then
        local f = assert(io.open(mpm.outdir .. "/started", "w"))
        f:close()
      end
    end }
    sim:run{ steps = 10000000 }
  end
elseif case == "files" then
  -- the deck's own files: written once (process 0) unless mpm.parallel_io("every")
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 1.2 }, cell = 0.1 }, thermo = 0 }
  local rank, dir = sim:parallel().rank, mpm.outdir .. "/"
  local f = assert(io.open(dir .. "once.txt", "w"))
  f:write("rank ", rank, "\n")
  f:close()
  f = assert(io.open(dir .. "once.txt", "a"))
  f:write("again rank ", rank, "\n")
  f:close()
  assert(io.open(dir .. "gone.txt", "w")):close()
  assert(os.remove(dir .. "gone.txt"))
  io.output(dir .. "output.txt")
  io.write("io.output rank ", rank, "\n")
  io.close()
  io.output(io.stdout)
  check(mpm.parallel_io("every") == "once", "the default is not once")
  f = assert(io.open(dir .. "every_" .. rank .. ".txt", "w"))
  f:write("rank ", rank, "\n")
  f:close()
  check(mpm.parallel_io("once") == "every", "the mode did not change")
  check(not pcall(mpm.parallel_io, "twice"), "parallel_io accepted 'twice'")
  print("files: written")
elseif case == "vtk_resume" then
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 1.0 }, cell = 0.05 }, gravity = { 0, -9.81 },
    dt = { cfl = 0.2 }, thermo = 0, name = case, boundary = { all = "slip" },
    output = { vtk = case, every_steps = 10, fields = { "velocity", "stress", "id" } } }
  sim:add_particles(mpm.box{ min = { 0.2, 0 }, max = { 0.8, 0.9 } }, { material = steel, per_axis = 2 })
  sim:run{ steps = 40, checkpoint = { every = 15 } }
elseif case == "small_grid" then
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.8 }, cell = 0.1 }, thermo = 0 }
  sim:add_particles(mpm.box{ min = { 0.2, 0 }, max = { 0.8, 0.5 } }, { material = steel, per_axis = 2 })
  sim:run{ steps = 5 }
elseif case == "cpdi_thin" then
  -- one particle per cell (domains of half a cell), the stretch F_yy = 1 + 4 t
  -- reaches 2 at t = 0.25 s
  mpm.warnings{ ignore = { "one_particle_per_cell" } }
  local sim = mpm.simulation{ dim = 2, grid = { size = { 0.4, 1.2 }, cell = 0.1 }, gravity = { 0, 0 }, shape = "cpdi",
    scheme = { transfer = "FLIP", stress_update = "USL" }, dt = { fixed = 0.01 }, thermo = 0, name = case }
  sim:add_particles(mpm.box{ min = { 0.1, 0.5 }, max = { 0.3, 0.7 } },
                    { material = mpm.material.neo_hookean{ density = 1000, E = 10, nu = 0.3 }, per_axis = 1,
                      velocity = function(x, y) return 0, 4 * (y - 0.6) end })
  sim:run{ steps = 100 }
else
  error("unknown case " .. tostring(case))
end
