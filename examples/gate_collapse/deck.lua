-- A granular column released by lifting a gate (2D plane strain).
--
-- A column of sand (000 Table 2, Mohr-Coulomb) 0.5 m wide and `ar` x 0.5 m
-- high stands against the left face, held on the right by a gate: a rigid
-- box wall 2 cm thick (`sim:add_wall`). It settles under gravity with
-- Cundall damping while the gate stands still, then the gate is lifted at a
-- constant speed and the column collapses onto a floor with Coulomb friction.
-- The deck repeats the collapse for each gate speed from the same settled
-- state and compares the runouts (000, Eqs. 70-72) with that of a gate
-- lifted so fast that it is gone before the column moves (the instantaneous
-- release of 000 §5 and of most simulations).
--
-- Parameters (--set key=value): speeds (m/s, comma-separated; default
-- 20,2,1,0.5: 20 m/s clears the column's height in 0.025 s), ar (1), cell
-- (0.025 m), mu (0.3, the floor), gate_mu (0: a smooth gate), settle (0.4 s),
-- t_max (t~ = t / sqrt(H / g) of the collapse, 8), quick (true: cell 0.05 m,
-- speeds 20,1, t~ 3, what ctest runs). Writes per speed the runout series
-- `gate_<v>.csv` (time, t~, front, L~, the gate's lift, E_k) and the final
-- particles `gate_<v>_final.csv` (x, y); `summary.csv`; plot.py draws them.
local quick = mpm.param("quick", false)
local ar = mpm.param("ar", 1.0)
local cell = mpm.param("cell", quick and 0.05 or 0.025)
local mu = mpm.param("mu", 0.3)
local gate_mu = mpm.param("gate_mu", 0.0)
local settle = mpm.param("settle", quick and 0.2 or 0.4)
local t_max = mpm.param("t_max", quick and 3 or 8)
local speeds = {}
for v in tostring(mpm.param("speeds", quick and "20,1" or "20,2,1,0.5")):gmatch("[^,]+") do
  speeds[#speeds + 1] = assert(tonumber(v), "speeds: numbers in m/s, comma-separated")
end

local W, H, g = 0.5, 0.5 * ar, 9.81
local thick = 0.02                      -- the gate's thickness (m)
local t_scale = math.sqrt(H / g)        -- 000, Eq. 73
local sand = require("moraine.presets").material("camargue_sand")

-- the column behind the gate, settled; returns the simulation
local function settled_column()
  local sim = mpm.simulation{ dim = 2, grid = { size = { W * 5, H + 0.3 }, cell = cell },
    shape = "cubic_bspline", shape_boundary = "modified", scheme = { transfer = "FLIP", stress_update = "USF" },
    gravity = { 0, -g }, dt = { a_tau = 0.2 }, damping = { cundall = 0.1 }, thermo = 0, diagnostics = false,
    boundary = { left = "slip", right = "slip", top = "free", bottom = { "friction", mu = mu } } }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { W, H } }, { material = sand, per_axis = 2,
                    stress = { -1, -1, -1, 0, 0, 0 } })
  -- the gate: from the floor to above the column, its left side against the sand
  sim:add_wall{ name = "gate", shape = "box", min = { W, 0 }, max = { W + thick, H + 0.2 },
                kind = gate_mu > 0 and "friction" or "slip", mu = gate_mu > 0 and gate_mu or nil }
  sim:run{ time = settle }
  sim:set_damping{ cundall = 0 }
  return sim
end

local function fmt(v) return (string.format("%g", v):gsub("%.", "p")) end

-- lift the gate at v (m/s) and let the column run out; returns the final L~
local function collapse(v)
  local sim = settled_column()
  sim:set_wall("gate", { velocity = { 0, v } })
  local name = "gate_" .. fmt(v)
  local series = assert(io.open(mpm.outdir .. "/" .. name .. ".csv", "w"))
  series:write("time,t_tilde,front,L_tilde,gate_bottom,E_kinetic\n")
  local t0, Lt = sim:time(), 0
  local lift_front -- the front when the gate clears the column
  local steps = 60
  for k = 1, steps do
    sim:run{ time = t_max * t_scale / steps }
    local t = sim:time() - t0
    local front = sim:reduce("max", "x")
    Lt = (front - W) / W -- 000, Eqs. 70-72
    local bottom = v * t
    if not lift_front and bottom >= H then lift_front = Lt end
    series:write(string.format("%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", t, t / t_scale, front, Lt, bottom,
                               sim:diagnostics().E_kinetic))
  end
  series:close()
  local final = assert(io.open(mpm.outdir .. "/" .. name .. "_final.csv", "w"))
  final:write("x,y\n")
  -- every particle of the run, on any number of processes
  local pos = sim:field("position", { gather = true })
  local xs = {}
  for i = 1, #pos // 3 do
    final:write(string.format("%.6g,%.6g\n", pos[3 * i - 2], pos[3 * i - 1]))
    xs[i] = pos[3 * i - 2]
  end
  final:close()
  -- the bulk front: 95 % of the particles (of equal mass) lie behind it
  table.sort(xs)
  local L95 = (xs[math.ceil(0.95 * #xs)] - W) / W
  local d = sim:diagnostics()
  sim:free()
  return Lt, L95, H / v, d
end

local summary = assert(io.open(mpm.outdir .. "/" .. "summary.csv", "w"))
summary:write("speed,lift_time,L_tilde,L_tilde_over_fastest,L_tilde_95,W_walls,W_MPM\n")
local fastest = math.max(table.unpack(speeds))
local L_fast
local rows = {}
for _, v in ipairs(speeds) do
  local Lt, L95, lift, d = collapse(v)
  rows[#rows + 1] = { v = v, Lt = Lt, L95 = L95, lift = lift, d = d }
  if v == fastest then L_fast = Lt end
end
print(string.format("gate collapse, AR %g, cell %g m, floor mu %g, gate mu %g, t~ = %g:", ar, cell, mu, gate_mu,
                       t_max))
for _, r in ipairs(rows) do
  local ratio = r.Lt / L_fast
  summary:write(string.format("%g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", r.v, r.lift, r.Lt, ratio, r.L95, r.d.W_walls,
                              r.d.W_MPM))
  print(string.format("  gate at %5g m/s (clears the column in %.3f s = %.2f t~): L~ = %.3f (%.3f x the fastest), " ..
                      "95 %% of the mass within L~ = %.3f; W_walls %.3g J/m, W_MPM %.3g J/m", r.v, r.lift,
                      r.lift / t_scale, r.Lt, ratio, r.L95, r.d.W_walls, r.d.W_MPM))
end
summary:close()
