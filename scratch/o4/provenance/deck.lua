-- Strip footing on a von Mises soil (002 §5.2): a rigid footing 1 m wide is
-- pushed 0.4 mm into a weightless cohesive soil (c = 10 kPa) and the footing
-- pressure rises to Prandtl's bearing capacity (2 + pi) c = 51.4 kPa.
-- Half the problem is simulated (symmetry face x = 0). See README.md.
--
--   moraine examples/strip_footing/deck.lua -o out/footing
--   moraine examples/strip_footing/deck.lua -o out/footing --set k=10 --set boundary=truncated
--
-- Parameters: k (constrained nodes 0..k under the half-footing, cell = 0.5 / (k + 0.5) m; 5),
-- transfer (TPIC), boundary (shape_boundary: wls), travel (m; 4e-4), vtk (true), quick (false).
local quick = mpm.param("quick", false)
local c = 10e3 -- cohesion (Pa); the soil is the preset footing_clay (002 §5.2: E = 1000 MPa, nu = 0.333, yield sqrt(3) c)
local B, L = 1.0, 5.0
local k = math.tointeger(mpm.param("k", quick and 2 or 5))
local h = (B / 2) / (k + 0.5)
local V, ramp = 4e-3, 0.02
local travel = quick and 2e-5 or mpm.param("travel", 4e-4)
local qu = (2 + math.pi) * c

local soil = require("moraine.presets").material("footing_clay", { yield = math.sqrt(3) * c }) -- von Mises, 002 Eq. 67
local sim = mpm.simulation{
  dim = 2,
  grid = { size = { L, L }, cell = h },
  shape = "quadratic_bspline",
  shape_boundary = mpm.param("boundary", "wls"),
  scheme = { transfer = mpm.param("transfer", "TPIC"), stress_update = "USF" },
  boundary = { left = "slip", right = "slip", bottom = "fixed", top = "free" },
  dt = { cfl = 1.0 },
  thermo = quick and 0 or 200,
  output = mpm.param("vtk", true) and { vtk = "footing", every = 0.01, fields = { "displacement", "stress", "von_mises", "eps_D" } } or nil,
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L, L } }, { material = soil, per_axis = 2 })
-- the footing: surface nodes with x < B/2 (their tributary lengths add up to B/2)
local footing = sim:constrain{ region = mpm.box{ min = { -1, L - 0.5 * h }, max = { B / 2 - 0.5 * h + 1e-9, L + 1 } }, vy = 0 }

local function speed(t) return t < ramp and V * 0.5 * (1 - math.cos(math.pi * t / ramp)) or V end
local function settlement(t)
  if t < ramp then return V * 0.5 * (t - ramp / math.pi * math.sin(math.pi * t / ramp)) end
  return V * (t - ramp / 2)
end
os.execute("mkdir -p '" .. mpm.outdir .. "'")
local csv = assert(io.open(mpm.outdir .. "/footing.csv", "w"))
csv:write("time,settlement,pressure,q_over_qu\n")
local last = 0
sim:hook{ every_steps = 1, fn = function(s)
  local t = s:time()
  if s:step() > 0 then
    last = -s:reaction(footing)[2] / (B / 2)
    csv:write(string.format("%.9g,%.9g,%.9g,%.6f\n", t, settlement(t), last, last / qu))
  end
  s:set_constraint(footing, { vy = -speed(t) })
end }
-- solve settlement(t) = travel for the end time
local t_end = travel >= V * ramp / 2 and travel / V + ramp / 2 or nil
if not t_end then
  local lo, hi = 0, ramp
  for _ = 1, 60 do
    local mid = 0.5 * (lo + hi)
    if settlement(mid) < travel then lo = mid else hi = mid end
  end
  t_end = hi
end
sim:run{ time = t_end }
csv:close()
print(string.format("strip footing: settlement %.3g mm, footing pressure %.4g kPa = %.4f (2 + pi) c (%d steps, cell %.4g m)",
                    1e3 * settlement(sim:time()), last / 1e3, last / qu, sim:step(), h))
