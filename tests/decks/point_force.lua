-- Point forces in the explicit step (sim:point_force, sim:load_factor,
-- sim:clear_forces; src/solver/point_force.c):
--  1. Newton's second law: a constant force on a few points of a free
--     elastic block (no gravity, no wall reached) changes the total momentum
--     by exactly F t (the transfers conserve momentum), to 1e-12 relative,
--     for PIC, FLIP and APIC; halving the load factor halves the rate.
--  2. Energy: point forces m_p g on every point of an elastic column that
--     falls on a slip floor are gravity by another road: the same motion
--     (positions to 1e-12 of the drop) and their work W_ext equals the fall
--     in E_g of the gravity run to 1e-10 relative, so W_MPM (000, Eq. 68)
--     is the same in both. For the free block of 1. W_MPM / W_ext is
--     reported (the sudden corner load excites the grid's highest modes;
--     PIC dissipates, 000 §3).
--  3. A traction p on the top face of a column on a frictionless floor,
--     settled with Cundall damping, gives sigma_yy = -p at mid-height
--     within 1 % (traction times each point's face V0^((dim-1)/dim)).
--  4. A checkpoint keeps the forces and the load factor: save, load and
--     step on gives the same momentum, bit for bit, as stepping on.
--  5. Errors: both force and traction, an empty region.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local F = { 30, -40 }

local function block(transfer)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 4, 4 }, cell = 0.1 }, gravity = { 0, 0 }, thermo = 0,
                              diagnostics = false, scheme = { transfer = transfer, stress_update = "USL" },
                              dt = { fixed = 1e-3 } }
  sim:add_particles(mpm.box{ min = { 1.5, 1.5 }, max = { 2.5, 2.5 } }, { material = mat, per_axis = 2 })
  local n = sim:point_force{ region = mpm.box{ min = { 2.4, 2.4 }, max = { 2.5, 2.5 } }, force = F }
  T.check(n == 4, "%d points loaded, expected the 4 of the corner cell", n)
  return sim
end

for _, transfer in ipairs{ "PIC", "FLIP", "APIC" } do
  local sim = block(transfer)
  sim:run{ steps = 200 }
  local p = sim:diagnostics().momentum
  local t = sim:time()
  for d = 1, 2 do T.close(p[d], F[d] * t, 1e-12, transfer .. string.format(" momentum %d = F t", d)) end
  sim:load_factor(0.5)
  sim:run{ steps = 100 }
  local p2 = sim:diagnostics().momentum
  for d = 1, 2 do
    T.close(p2[d] - p[d], 0.5 * F[d] * (sim:time() - t), 1e-10, transfer .. " momentum rate at load factor 0.5")
  end
  local e = sim:energy()
  T.check(e.external > 0, "%s: the work of the point forces is %g, expected positive", transfer, e.external)
  local balance = math.abs(e.mpm_error) / e.external
  print(string.format("point_force %s: momentum %.6g %.6g, W_ext %.6g J/m, E_k %.6g, E_el %.6g, W_MPM %.3g (%.3g of W_ext)",
                      transfer, p2[1], p2[2], e.external, e.kinetic, e.elastic, e.mpm_error, balance))
  T.expect{ id = "point_force.balance_" .. transfer, what = transfer .. ": |W_MPM| / W_ext, sudden corner load",
            value = 100 * balance, unit = "%" }
  sim:clear_forces()
  local before = sim:diagnostics().momentum
  sim:run{ steps = 10 }
  local after = sim:diagnostics().momentum
  T.close(after[1], before[1], 1e-12, transfer .. " momentum without forces")
  sim:free()
end

-- 2. gravity as point forces
do
  local rho, g = 1000, 9.81
  local function column(as_forces)
    local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1.5 }, cell = 0.05 }, gravity = { 0, as_forces and 0 or -g },
      scheme = { transfer = "FLIP", stress_update = "USL" }, dt = { fixed = 2e-4 },
      boundary = { all = "slip" }, thermo = 0, diagnostics = false }
    sim:add_particles(mpm.box{ min = { 0.3, 0.2 }, max = { 0.7, 1.0 } }, { material = mat, per_axis = 2 })
    if as_forces then
      local m = 0.4 * 0.8 * rho
      sim:point_force{ region = mpm.box{ min = { 0, 0 }, max = { 1, 1.5 } }, force = { 0, -m * g } }
    end
    local e0 = sim:energy()
    sim:run{ time = 0.4 } -- falls 0.2 m onto the floor at t = 0.2 s and bounces
    return sim, e0
  end
  local a, a0 = column(false)
  local b = column(true)
  local ea, eb = a:energy(), b:energy()
  local worst = 0
  for i = 1, a:particle_count() do
    local pa, pb = a:particle(i), b:particle(i)
    for d = 1, 2 do worst = math.max(worst, math.abs(pa.x[d] - pb.x[d])) end
  end
  T.check(worst <= 1e-12 * 0.2, "positions under gravity and under point forces m g differ by %.3g m", worst)
  local drop = -(ea.gravity - a0.gravity) -- work of gravity
  T.close(eb.external, drop, 1e-10, "W_ext of the point forces m g against the work of gravity")
  T.close(eb.mpm_error, ea.mpm_error, 1e-6, "W_MPM with point forces against W_MPM with gravity", 1e-12 * drop)
  print(string.format("point_force gravity: positions within %.3g m, W_ext %.12g J/m, gravity work %.12g J/m, " ..
                      "W_MPM %.4g vs %.4g J/m", worst, eb.external, drop, eb.mpm_error, ea.mpm_error))
  a:free()
  b:free()
end

-- 3. traction on a column
do
  local p, H = 2e4, 1.0
  local sim = mpm.simulation{ dim = 2, grid = { size = { 0.4, 1.2 }, cell = 0.05 }, gravity = { 0, 0 },
    scheme = { transfer = "FLIP", stress_update = "USF" }, dt = { a_tau = 0.2 }, damping = { cundall = 0.1 },
    boundary = { left = "slip", right = "slip", bottom = "slip", top = "free" }, thermo = 0, diagnostics = false }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 0.4, H } }, { material = mat, per_axis = 2 })
  sim:point_force{ region = mpm.box{ min = { 0, H - 0.025 }, max = { 0.4, H } }, traction = { 0, -p } }
  sim:run{ time = 1.0 }
  local s, n = 0, 0
  for i = 1, sim:particle_count() do
    local q = sim:particle(i)
    if math.abs(q.x[2] - 0.5 * H) < 0.1 then s, n = s + q.stress[2], n + 1 end
  end
  T.expect{ id = "point_force.traction", what = "sigma_yy at mid-height under a top traction", value = s / n,
            reference = -p, rtol = 0.01, unit = "Pa" }
  local e = sim:energy()
  print(string.format("point_force traction: sigma_yy %.6g Pa (traction %g), W_ext %.4g, W_damp %.4g, W_MPM %.3g J/m",
                      s / n, p, e.external, e.damping, e.mpm_error))
  sim:free()
end

-- 4. checkpoint
do
  local sim = block("FLIP")
  sim:load_factor(0.75)
  sim:run{ steps = 50 }
  local path = sim:save("point_force_50.h5")
  sim:run{ steps = 50 }
  local straight = sim:diagnostics()
  local resumed = mpm.load(path, { diagnostics = false, thermo = 0 })
  resumed:run{ steps = 50 }
  local again = resumed:diagnostics()
  for d = 1, 2 do
    T.check(again.momentum[d] == straight.momentum[d], "resumed momentum %.17g differs from %.17g",
            again.momentum[d], straight.momentum[d])
  end
  T.check(again.W_external == straight.W_external, "resumed W_ext %.17g differs from %.17g", again.W_external,
          straight.W_external)
  T.check(resumed:value("point_force", 1)[1] == sim:value("point_force", 1)[1], "point forces not restored")
  sim:free()
  resumed:free()
end

-- 5. errors
do
  local sim = block("PIC")
  local ok, msg = pcall(sim.point_force, sim, { region = mpm.box{ min = { 0, 0 }, max = { 1, 1 } }, force = F })
  T.check(not ok and msg:find("holds no material point"), "empty region: %s", tostring(msg))
  ok, msg = pcall(sim.point_force, sim, { region = mpm.box{ min = { 0, 0 }, max = { 4, 4 } }, force = F, traction = F })
  T.check(not ok and msg:find("exactly one of force and traction"), "force and traction: %s", tostring(msg))
  ok, msg = pcall(sim.particle_field, sim, { name = "point_force" })
  T.check(not ok and msg:find("reserved"), "reserved name: %s", tostring(msg))
  sim:free()
end
T.done("point_force")
