-- Bouncing cube (000 §4.1, Fig. 3) for several strategies with USF: the
-- energy after the first bounce and how high the cube comes back up.
-- FLIP keeps the total energy within 3 %; AFLIP and TFLIP lose about 5 % per
-- bounce at most; PIC, APIC and TPIC do not bounce (back above half the drop
-- height); XPIC(m), m = 2..4, sits between PIC and FLIP (000 §3.3). Each
-- strategy's energy curve goes to cube_<strategy>.csv for plotting.
-- --set strategies=FLIP,PIC picks some; --set time=T sets the run length.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }
local duration = mpm.param("time", 1.0)

local function bounce(transfer)
  local sim = mpm.simulation{
    dim = 3, grid = { size = { 1, 1, 2.6 }, cell = 0.2 }, gravity = { 0, 0, -9.81 },
    scheme = { transfer = transfer, stress_update = "USF" }, dt = { a_tau = 0.05 },
    boundary = { all = "slip", top = "free" }, thermo = 0,
    diagnostics = "cube_" .. transfer:gsub("[()]", "") .. ".csv", diagnostics_every = 20,
  }
  sim:add_particles(mpm.box{ min = { 0, 0, 1 }, max = { 1, 1, 2 } }, { material = mat, per_axis = 2 })
  local e0 = sim:energy().total
  local impact, top, worst = false, -math.huge, 0
  sim:hook{ every_steps = 10, fn = function(s)
    local d = s:diagnostics()
    worst = math.max(worst, math.abs(d.E_total - e0) / e0)
    if s:time() > 0.1 and d.com_velocity[3] >= 0 then impact = true end
    if impact then top = math.max(top, d.center_of_mass[3]) end
  end }
  sim:run{ time = duration }
  local loss = 1 - sim:energy().total / e0
  sim:free()
  return { loss = loss, top = top, worst = worst, impact = impact }
end

local list = {}
for name in mpm.param("strategies", "PIC,FLIP,APIC,AFLIP,TPIC,TFLIP,XPIC(2),XPIC(3),XPIC(4)"):gmatch("[^,]+") do
  list[#list + 1] = name
end
local r = {}
for _, name in ipairs(list) do
  r[name] = bounce(name)
  print(string.format("bouncing cube %-8s energy lost %6.2f %%, largest drift %6.2f %%, back up to z_c = %.3f m",
                      name, 100 * r[name].loss, 100 * r[name].worst, r[name].top))
  T.check(r[name].impact, "%s: the cube never reached the floor", name)
end
local id = "bouncing_cube_strategies."
if r.FLIP then
  T.expect{ id = id .. "FLIP.drift", what = string.format("FLIP largest energy drift over %g s", duration),
            value = 100 * r.FLIP.worst, max = 3, unit = "%" }
end
for _, name in ipairs{ "AFLIP", "TFLIP" } do
  if r[name] then
    T.expect{ id = id .. name .. ".loss", what = string.format("%s energy lost over %g s (000: about 5 %% per bounce)", name, duration),
              value = 100 * r[name].loss, max = 6, unit = "%" }
  end
end
for _, name in ipairs{ "PIC", "APIC", "TPIC" } do
  if r[name] then
    T.expect{ id = id .. name .. ".top", what = name .. ": highest centre of mass after the impact (does not bounce: below 1.0 m)",
              value = r[name].top, max = 1.0, unit = "m" }
  end
end
if r.PIC and r.FLIP then
  for m = 2, 4 do
    local x = r["XPIC(" .. m .. ")"]
    if x then
      T.expect{ id = id .. "XPIC" .. m .. ".loss",
                what = string.format("XPIC(%d) energy lost over %g s, between FLIP's and PIC's", m, duration),
                value = 100 * x.loss, min = 100 * r.FLIP.loss, max = 100 * r.PIC.loss, unit = "%" }
    end
  end
end
T.done("bouncing_cube_strategies")
