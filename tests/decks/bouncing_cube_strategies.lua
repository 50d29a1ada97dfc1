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
if r.FLIP then T.check(r.FLIP.worst < 0.03, "FLIP drifted %.2f %% (limit 3 %%)", 100 * r.FLIP.worst) end
for _, name in ipairs{ "AFLIP", "TFLIP" } do
  if r[name] then T.check(r[name].loss < 0.06, "%s lost %.2f %% in one bounce (about 5 %% at most)", name, 100 * r[name].loss) end
end
for _, name in ipairs{ "PIC", "APIC", "TPIC" } do
  if r[name] then T.check(r[name].top < 1.0, "%s bounced back to %.3f m (limit 1.0 m, half the drop)", name, r[name].top) end
end
if r.PIC and r.FLIP then
  for m = 2, 4 do
    local x = r["XPIC(" .. m .. ")"]
    if x then
      T.check(x.loss > r.FLIP.loss and x.loss < r.PIC.loss, "XPIC(%d) lost %.2f %%, not between FLIP (%.2f %%) and PIC (%.2f %%)",
              m, 100 * x.loss, 100 * r.FLIP.loss, 100 * r.PIC.loss)
    end
  end
end
T.done("bouncing_cube_strategies")
