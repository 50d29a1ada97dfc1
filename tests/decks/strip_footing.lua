-- Strip footing on a von Mises (Tresca in plane strain) soil (002 §5.2):
-- E = 1000 MPa, nu = 0.333, rho = 1000 kg/m^3, cohesion c = 10 kPa, so
-- yield = sqrt(3) c (002 Eq. 67); no gravity (Prandtl's weightless soil).
-- A rigid footing of width B = 1 m is pushed 0.4 mm into the surface at
-- 4 mm/s; by symmetry half of it is simulated: a 5 m x 5 m half-domain, the
-- symmetry face x = 0 is `slip`, the far side `slip`, the base `fixed`, the
-- surface `free`. Quadratic B-splines with the WLS kernel correction
-- (shape_boundary = "wls"), TPIC, USF, time step cfl = 1 (002 used C_r = 1).
-- Prandtl's bearing capacity (002 Eq. 65) is q_u = (2 + pi) c = 51.42 kPa.
--
-- The footing: `sim:constrain` prescribes vy on the surface nodes under it
-- (vx is left free: a smooth footing). A row of constrained nodes 0..k carries
-- the load over their tributary length (k + 1/2) h, so the cell is chosen with
-- B/2 = (k + 1/2) h (h = B/11 here, B/21 for the full run) and the nodes with
-- x < B/2 are constrained; the footing pressure is q = -reaction_y / (B/2).
-- Loading: the footing speed rises from 0 to 4 mm/s along a half-cosine over
-- 0.02 s (an abrupt start sends a stress wave of rho c_p v = 4.9 kPa, 10 % of
-- q_u, through the soil), then stays at 4 mm/s until it has moved 0.4 mm. No
-- damping. q is taken as the mean over the last 10 % of the travel.
--
-- Asserts (issue 4 item 2): q within 5 % of (2 + pi) c. Quick (h = B/11,
-- 12100 particles, ~4 s): q/q_u = 1.0215; full (`--set full=true`, h = B/21,
-- 44100 particles, ~25 s): 1.0188. Not asserted, at h = B/11: FLIP 1.013,
-- APIC 1.020, MLS 1.054; TPIC with `--set boundary=truncated` 1.62 (002: far
-- from Prandtl without the correction), with `extended` ghost nodes 0.999.
-- The load-settlement curve goes to footing.csv in the output directory.
-- Parameters: full, k, transfer, boundary.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local full = mpm.param("full", false)
local E, nu, rho, c = 1e9, 0.333, 1000, 10e3
local B, L = 1.0, 5.0
local k = math.tointeger(mpm.param("k", full and 10 or 5)) -- constrained nodes 0..k under the half-footing
local h = (B / 2) / (k + 0.5)
local V, travel, ramp = 4e-3, 4e-4, 0.02
local transfer = mpm.param("transfer", "TPIC")
local boundary = mpm.param("boundary", "wls")
local qu = (2 + math.pi) * c

local soil = mpm.material.von_mises{ density = rho, E = E, nu = nu, yield = math.sqrt(3) * c }
local sim = mpm.simulation{ dim = 2, grid = { size = { L, L }, cell = h }, shape = "quadratic_bspline",
  shape_boundary = boundary, scheme = { transfer = transfer, stress_update = "USF" },
  boundary = { left = "slip", right = "slip", bottom = "fixed", top = "free" },
  dt = { cfl = 1.0 }, thermo = 0, diagnostics = false }
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L, L } }, { material = soil, per_axis = 2 })
local footing = sim:constrain{ region = mpm.box{ min = { -1, L - 0.5 * h }, max = { B / 2 - 0.5 * h + 1e-9, L + 1 } },
                               vy = 0 }

local function speed(t) return t < ramp and V * 0.5 * (1 - math.cos(math.pi * t / ramp)) or V end
local function settlement(t) -- integral of speed
  if t < ramp then return V * 0.5 * (t - ramp / math.pi * math.sin(math.pi * t / ramp)) end
  return V * (t - ramp / 2)
end
local curve = {}
sim:hook{ every_steps = 1, fn = function(s)
  local t = s:time()
  if s:step() > 0 then curve[#curve + 1] = { settlement(t), -s:reaction(footing)[2] / (B / 2) } end
  s:set_constraint(footing, { vy = -speed(t) }) -- for the next step
end }
local t_end = travel / V + ramp / 2 -- settlement(t_end) = travel
sim:run{ time = t_end }

os.execute("mkdir -p '" .. mpm.outdir .. "'")
local f = assert(io.open(mpm.outdir .. "/footing.csv", "w"))
f:write("settlement_m,pressure_Pa,pressure_over_qu\n")
local sum, n, peak = 0, 0, 0
for _, p in ipairs(curve) do
  f:write(string.format("%.9g,%.9g,%.6f\n", p[1], p[2], p[2] / qu))
  if p[1] >= 0.9 * travel then sum, n = sum + p[2], n + 1 end
  peak = math.max(peak, p[2])
end
f:close()
local q = sum / n
print(string.format("strip footing %s + %s, h = B/%d (%d particles, %d steps): q = %.1f Pa, q/q_u = %.4f (peak %.4f); q_u = (2 + pi) c = %.1f Pa",
  transfer, boundary, 2 * k + 1, sim:particle_count(), sim:step(), q, q / qu, peak / qu, qu))
T.expect{ id = string.format("strip_footing.%s_%s_B%d", transfer, boundary, 2 * k + 1),
          what = string.format("footing pressure, %s + %s, h = B/%d", transfer, boundary, 2 * k + 1),
          value = q, reference = qu, rtol = 0.05, unit = "Pa", asserted = boundary == "wls" }
T.done("strip_footing")
