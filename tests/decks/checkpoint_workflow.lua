-- Checkpoints from a deck (000 §5's settle-then-collapse workflow):
--  1. restart: N steps, save, load, N more steps gives particle state
--     bitwise identical to 2N steps straight, for an elastic and a
--     Mohr-Coulomb case with Cundall damping and a CFL time step;
--  2. import: the settled column moved onto a 6x wider grid with a
--     Mohr-Coulomb material keeps positions and stresses exactly, and the
--     collapse starts from rest (kinetic energy after the first collapse
--     step below 1e-6 of the potential-energy drop of the settling, 000 Eq. 69).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local elastic = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }
local sand = mpm.material.mohr_coulomb{ density = 1748, E = 12.84e6, nu = 0.16, phi = 33.75, psi = 0, cohesion = 1 }

local function column(material, name)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 1.5 }, cell = 0.1 }, gravity = { 0, -9.81 },
    shape = "cubic_bspline", shape_boundary = "modified", scheme = { transfer = "FLIP", stress_update = "USF" },
    dt = { cfl = 0.4 }, damping = { cundall = 0.1 }, boundary = { all = "slip", top = "free" },
    thermo = 0, diagnostics = name .. ".csv", name = name }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 1, 1 } }, { material = material, per_axis = 2 })
  return sim
end

local function same_state(a, b, label)
  for _, f in ipairs{ "velocity", "displacement", "stress", "strain", "volume", "deformation_gradient", "id" } do
    local x, y = a:field(f), b:field(f)
    T.check(#x == #y, "%s: %s sizes differ", label, f)
    for i = 1, #x do
      if x[i] ~= y[i] then T.check(false, "%s: %s[%d] differs: %.17g vs %.17g", label, f, i, x[i], y[i]) end
    end
  end
  T.check(a:time() == b:time() and a:step() == b:step(), "%s: clocks differ", label)
end

-- 1. restart, bitwise
for _, case in ipairs{ { elastic, "elastic" }, { sand, "mohr_coulomb" } } do
  local straight = column(case[1], case[2] .. "_straight")
  straight:run{ steps = 60 }
  local path = straight:save(case[2] .. "_60.h5")
  straight:run{ steps = 60 }
  local resumed = mpm.load(path, { diagnostics = false, thermo = 0 })
  resumed:run{ steps = 60 }
  same_state(straight, resumed, case[2] .. " restart")
  print(string.format("restart %-12s: 60 + 60 steps bitwise identical to 120 straight (t = %.5f s)", case[2], resumed:time()))
end

-- 2. settle elastically, then import onto a 6x wider grid as Mohr-Coulomb
local settle = column(elastic, "settle")
local e0 = settle:energy()
settle:run{ time = mpm.param("settle_time", 1.5) }
local e1 = settle:energy()
local drop = math.abs((e1.gravity + e1.elastic) - (e0.gravity + e0.elastic))
local settled = settle:save("settled.h5")
local collapse = mpm.simulation{ dim = 2, grid = { size = { 6, 1.5 }, cell = 0.1 }, gravity = { 0, -9.81 },
  shape = "cubic_bspline", shape_boundary = "modified", scheme = { transfer = "FLIP", stress_update = "USF" },
  dt = { cfl = 0.4 }, boundary = { all = "slip", top = "free", right = "free", bottom = { "friction", mu = 0.3 } },
  thermo = 0, diagnostics = "collapse.csv", name = "collapse" }
local n = collapse:import(settled, { material = sand })
T.check(n == settle:particle_count(), "imported %d of %d particles", n, settle:particle_count())
local xs, xc = settle:field("displacement"), collapse:field("displacement")
local ss, sc = settle:field("stress"), collapse:field("stress")
for i = 1, #xs do T.check(xs[i] == xc[i], "position %d changed on import", i) end
for i = 1, #ss do T.check(ss[i] == sc[i], "stress %d changed on import", i) end
-- the collapse starts from the settled state at rest: its kinetic energy at
-- the first collapse step (before the first update moves anything)
local ek = collapse:energy().kinetic
T.check(ek < 1e-6 * drop, "kinetic energy %.3g J/m after the first collapse step is not below 1e-6 of the drop %.4g J/m",
        ek, drop)
print(string.format("import: %d particles kept positions and stresses exactly; E_k at the start %.3g J/m (drop %.4g J/m)",
                    n, ek, drop))
T.done("checkpoint_workflow")
