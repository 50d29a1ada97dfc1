-- Bouncing cube (000 §4.1) under every stress update x PIC, FLIP, APIC,
-- TPIC at two time steps: the energy through the first bounce.
-- 000 §3.4, after Nairn: USAVG "conserves almost perfectly the energy";
-- here its FLIP energy drift must stay below USF's at the same dt and at
-- least halve with dt (the stress and velocity are leapfrog, second order,
-- but the particle positions, shared by every scheme, are first order: the
-- free fall alone loses m g^2 t dt / 2). 000 App. A: USL is strictly dissipative (every strategy loses
-- energy, FLIP more than under USF). PIC, APIC and TPIC lose about half the
-- energy at the impact whatever the stress update (000 Fig. 3, Fig. 23),
-- checked under each update.
-- Each run's energies go to upd_<update>_<strategy>_<a_tau>.csv.
-- --set updates=..., strategies=..., a_tau=0.05,0.025, time=T pick a part.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }
local duration = mpm.param("time", 0.9)

local function list(text)
  local out = {}
  for item in text:gmatch("[^,]+") do out[#out + 1] = item end
  return out
end

local function bounce(update, transfer, a_tau)
  local sim = mpm.simulation{
    dim = 3, grid = { size = { 1, 1, 2.6 }, cell = 0.2 }, gravity = { 0, 0, -9.81 },
    scheme = { transfer = transfer, stress_update = update }, dt = { a_tau = a_tau },
    boundary = { all = "slip", top = "free" }, thermo = 0,
    diagnostics = string.format("upd_%s_%s_%s.csv", update, transfer, a_tau), diagnostics_every = 20,
  }
  sim:add_particles(mpm.box{ min = { 0, 0, 1 }, max = { 1, 1, 2 } }, { material = mat, per_axis = 2 })
  local e0 = sim:energy().total
  local worst, impact = 0, false
  sim:hook{ every_steps = 10, fn = function(s)
    local d = s:diagnostics()
    worst = math.max(worst, math.abs(d.E_total - e0) / e0)
    if s:time() > 0.1 and d.com_velocity[3] >= 0 then impact = true end
  end }
  sim:run{ time = duration }
  local r = { loss = 100 * (1 - sim:energy().total / e0), drift = 100 * worst, impact = impact }
  sim:free()
  return r
end

local updates = list(mpm.param("updates", "USF,USL,MUSL,USAVG"))
local strategies = list(mpm.param("strategies", "PIC,FLIP,APIC,TPIC"))
local steps = list(mpm.param("a_tau", "0.05,0.025"))
local r = {}
for _, a_tau in ipairs(steps) do
  for _, update in ipairs(updates) do
    for _, transfer in ipairs(strategies) do
      local key = update .. "." .. transfer .. "." .. a_tau
      r[key] = bounce(update, transfer, tonumber(a_tau))
      print(string.format("bouncing cube %-5s %-4s a_tau %-6s energy lost %7.3f %%, largest drift %7.3f %%",
                          update, transfer, a_tau, r[key].loss, r[key].drift))
      T.check(r[key].impact, "%s: the cube never reached the floor", key)
      T.expect{ id = "bouncing_cube_updates." .. key .. ".loss", detail = true, value = r[key].loss, unit = "%",
                what = string.format("%s + %s, a_tau = %s: energy lost over %g s", update, transfer, a_tau, duration) }
    end
  end
end

local id = "bouncing_cube_updates."
for _, a_tau in ipairs(steps) do
  local usf, usavg = r["USF.FLIP." .. a_tau], r["USAVG.FLIP." .. a_tau]
  if usf and usavg then
    T.expect{ id = id .. "USAVG_vs_USF." .. a_tau, unit = "%", value = usavg.drift, max = usf.drift,
              what = string.format("FLIP + USAVG largest energy drift, a_tau = %s (000 §3.4: below USF's, %.3g %%)",
                                   a_tau, usf.drift) }
  end
  for _, transfer in ipairs(strategies) do
    local usl = r["USL." .. transfer .. "." .. a_tau]
    if usl then
      T.expect{ id = id .. "USL_loses." .. transfer .. "." .. a_tau, unit = "%", value = usl.loss, min = 0,
                what = string.format("USL + %s energy lost, a_tau = %s (000 App. A: strictly dissipative)",
                                     transfer, a_tau) }
    end
    for _, update in ipairs(updates) do
      local pic = transfer ~= "FLIP" and r[update .. "." .. transfer .. "." .. a_tau]
      if pic then
        T.expect{ id = id .. update .. "_pic_family." .. transfer .. "." .. a_tau, unit = "%", value = pic.loss, min = 40,
                  what = string.format("%s + %s energy lost, a_tau = %s (000 Fig. 3: the PIC family does not bounce)",
                                       update, transfer, a_tau) }
      end
    end
  end
  local usl = r["USL.FLIP." .. a_tau]
  if usl and usf then
    T.expect{ id = id .. "USL_vs_USF." .. a_tau, unit = "%", value = usl.loss, min = usf.drift,
              what = string.format("FLIP + USL energy lost, a_tau = %s (000 App. A: more than USF's drift, %.3g %%)",
                                   a_tau, usf.drift) }
  end
end
local coarse, fine = steps[1], steps[2]
if fine and tonumber(fine) == tonumber(coarse) / 2 and r["USAVG.FLIP." .. coarse] and r["USAVG.FLIP." .. fine] then
  local ratio = r["USAVG.FLIP." .. coarse].drift / r["USAVG.FLIP." .. fine].drift
  T.expect{ id = id .. "USAVG_order", value = ratio, min = 1.8,
            what = string.format("FLIP + USAVG: drift at a_tau = %s over drift at %s (first order: 2)", coarse, fine) }
end
T.done("bouncing_cube_updates")
