-- Extrusion of a viscous melt through a converging nozzle (004 §4): a
-- Newtonian melt (eta = 138.9 Pa s, bulk modulus 1 GPa, rho = 1000 kg/m^3)
-- fills a 25.4 mm high barrel and the nozzle; an inflow source pushes it at 2.7 mm/s
-- through a symmetric nozzle into a 5 mm channel, out of whose end it
-- leaves through the free right face (on_leave = "delete"). The die is two
-- polygon walls with no slip. Mass scaling brings the step to 004's 0.6 ms.
-- 004 found that FLIP with 1 % PIC goes unstable at once, FLIP with 20 %
-- PIC runs but damps the flow after the nozzle into a plug, and APIC keeps
-- the converging flow; the deck runs one transfer and reports how far it
-- got. See README.md.
--
--   moraine examples/extrusion/deck.lua -o out/extrusion
--   moraine examples/extrusion/deck.lua -o out/extrusion --set transfers=FLIP0.99
--
-- Parameters: transfers (comma-separated; APIC,FLIP0.99,FLIP0.8), cell (m;
-- 8e-4, 004 uses 1e-4), time (s; 15), dt (s; 6e-4), vtk (true), quick
-- (false; true: APIC only, 1 s, asserted).
local quick = mpm.param("quick", false)
local transfers = {}
for item in mpm.param("transfers", quick and "APIC" or "APIC,FLIP0.99,FLIP0.8"):gmatch("[^,%s]+") do
  transfers[#transfers + 1] = item
end
local vtk = mpm.param("vtk", true)
local h = mpm.param("cell", 8e-4)
local T = mpm.param("time", quick and 1.0 or 15.0)
local dt = mpm.param("dt", 6e-4)
local rho, eta, K, v_in = 1000.0, 138.9, 1.0e9, 2.7e-3 -- 004 §4

-- the die, along x: barrel (25.4 mm) up to x1, nozzle (a straight taper)
-- up to x2, channel (5 mm) up to the grid's end; m cells of wall around
local H_in, H_out = 25.4e-3, 5.0e-3
local x1, x2 = 10e-3, 30e-3
local L = math.ceil(90e-3 / h - 1e-9) * h -- whole cells
local Hg = (math.ceil(H_in / h - 1e-9) + 6) * h -- three cells of wall or more on each side
local yc = Hg / 2 -- the die's axis
local function top(x) -- the die's upper contour
  if x <= x1 then return yc + H_in / 2 end
  if x >= x2 then return yc + H_out / 2 end
  return yc + H_in / 2 + (H_out - H_in) / 2 * (x - x1) / (x2 - x1)
end

-- the stable step of the melt's sound speed, and the mass scaling that
-- brings it to dt (mass_scaling: the step grows by sqrt(f))
local c = math.sqrt(K / rho)
local cfl = 0.3
local f = math.max(1, (dt / (cfl * h / c)) ^ 2)

local melt = mpm.material.newtonian{ density = rho, viscosity = eta, sound_speed = c }

-- the die: upper and lower walls, mirror images about the axis; they reach
-- a cell beyond the grid's ends so the corners are not edges of the die
local upper, lower = {}, {}
for _, x in ipairs({ -h, x1, x2, L + h }) do
  upper[#upper + 1] = { x, top(x) }
  lower[#lower + 1] = { x, 2 * yc - top(x) }
end
upper[#upper + 1] = { L + h, Hg + h }
upper[#upper + 1] = { -h, Hg + h }
lower[#lower + 1] = { L + h, -h }
lower[#lower + 1] = { -h, -h }

local inlet = 2 * h -- the source's inlet: two cells at x = 0
local fill = mpm.polygon{ vertices = { { inlet, 2 * yc - top(0) }, { x1, 2 * yc - top(x1) }, { x2, 2 * yc - top(x2) },
                                      { x2, top(x2) }, { x1, top(x1) }, { inlet, top(0) } } }
local probe = mpm.box{ min = { x2 + 5 * h, 0 }, max = { x2 + 15 * h, Hg } }

local function build(transfer)
  local tag = transfer:gsub("[^%w]", "_")
  local sim = mpm.simulation{
    dim = 2,
    grid = { size = { L, Hg }, cell = h },
    gravity = { 0, 0 },
    scheme = { transfer = transfer, stress_update = "USF" },
    boundary = { all = "slip", right = "free" },
    on_leave = "delete",
    mass_scaling = f,
    dt = dt,
    thermo = quick and 0 or 2500,
    name = tag,
    diagnostics = tag .. "_diagnostics.csv",
    output = vtk and { vtk = tag, every = quick and 0.5 or 1.0, fields = { "velocity", "pressure" } } or nil,
  }
  sim:add_wall{ name = "upper", shape = "polygon", vertices = upper, kind = "fixed" }
  sim:add_wall{ name = "lower", shape = "polygon", vertices = lower, kind = "fixed" }
  -- the barrel and the nozzle are full of melt; the source makes new melt
  -- as the inflow crosses its inlet
  sim:add_source{ name = "feed", region = mpm.box{ min = { 0, yc - H_in / 2 }, max = { inlet, yc + H_in / 2 } },
                  material = melt, face = "xmin", velocity = { v_in, 0 }, per_axis = 2 }
  sim:add_particles(fill, { material = melt, per_axis = 2 })
  return sim, tag
end

-- the mean speed of the particles across the channel, 5-15 cells past the nozzle
local function channel_speed(s) return s:reduce("mean", "velocity", { component = 1, region = probe }) or 0 end

-- one transfer: a CSV of the flow every 0.5 s; nil, or the time it failed
local function extrude(transfer)
  local sim, tag = build(transfer)
  local m0 = sim:diagnostics().mass
  local csv = assert(io.open(mpm.outdir .. "/" .. tag .. ".csv", "w"))
  csv:write("t,mass,inflow_mass,outflow_mass,front,channel_speed\n")
  sim:hook{ every_time = quick and 0.25 or 0.5, fn = function(s)
    local d = s:diagnostics()
    csv:write(string.format("%.4f,%.9g,%.9g,%.9g,%.9g,%.9g\n", s:time(), d.mass, d.inflow_mass, d.outflow_mass,
                            s:reduce("max", "x"), channel_speed(s)))
    csv:flush()
  end }
  local ok, err = pcall(sim.run, sim, { time = T })
  csv:close()
  if not ok and not tostring(err):find("run{}: step") then error(err, 0) end -- a fault of the deck
  if not ok then
    print(string.format("extrusion: %s became unstable at t = %.3f s (step %d): %s", transfer, sim:time(),
                        sim:step(), tostring(err)))
    return sim:time()
  end
  local d = sim:diagnostics()
  print(string.format("extrusion: %s ran to t = %.2f s; melt fed %.5g kg/m (rho A v t = %.5g), extruded %.5g kg/m",
                      transfer, sim:time(), d.inflow_mass, rho * H_in * v_in * sim:time(), d.outflow_mass))
  print(string.format("extrusion: %s: mean speed in the channel %.2f mm/s; the feed's flux over its height %.2f mm/s",
                      transfer, channel_speed(sim) * 1e3, v_in * H_in / H_out * 1e3))
  if quick then
    -- what must hold: the mass balance, and the feed within one layer of rho A v t
    local layer = rho * H_in * h / 2
    assert(math.abs(m0 + d.inflow_mass - d.outflow_mass - d.mass) <= 1e-12 * d.mass,
           "extrusion: initial + fed - extruded differs from the mass in the die")
    assert(math.abs(d.inflow_mass - rho * H_in * v_in * sim:time()) <= layer,
           string.format("extrusion: fed %.6g kg/m, rho A v t = %.6g, more than a layer apart", d.inflow_mass,
                         rho * H_in * v_in * sim:time()))
  end
end

print(string.format("extrusion: cells of %.2f mm, mass scaling %.3g for dt = %.2g ms, %g s", h * 1e3, f, dt * 1e3, T))
for _, transfer in ipairs(transfers) do extrude(transfer) end
