-- A rigid strip footing pushed into a weightless cohesive soil by a wall of
-- prescribed motion (plane strain), against Prandtl's bearing capacity
-- q_u = (2 + pi) c. The soil is that of examples/strip_footing (002 §5.2):
-- von Mises with yield = sqrt(3) c (a Tresca soil of cohesion c in plane
-- strain), c = 10 kPa, E = 1000 MPa, nu = 0.333, rho = 1000 kg/m^3, no
-- gravity; `--set material=mohr_coulomb` takes Mohr-Coulomb with phi = psi = 0
-- instead. Half of the problem by symmetry: a 5 m x 5 m block, the footing's
-- half-width B/2 = 0.5 m at the top left corner; the symmetry face x = 0 and
-- the far side `slip`, the base `fixed`, the surface `free`.
--
-- The footing is a box wall (sim:add_wall) from x = -2h to B/2 whose base
-- lies on the surface, `slip` (a smooth footing) or, with `--set rough=true`,
-- `fixed` (a rough one: for phi = 0 Prandtl's q_u holds for both). It moves
-- down at V = 4 mm/s, reached along a half-cosine over 0.02 s (an abrupt start
-- sends a stress wave of rho c_p V, 10 % of q_u, through the soil). The
-- footing pressure is the wall's vertical reaction per metre over the
-- half-width, q = force_y / (B/2); the cell h = B / (2k + 1) puts the footing's
-- edge halfway between two nodes, so the nodes under it carry exactly B/2.
-- Quadratic B-splines with the WLS kernel correction at the faces, TPIC + USF,
-- cfl = 1.
--
--   moraine examples/prandtl_footing/deck.lua -o out/prandtl
--   moraine examples/prandtl_footing/deck.lua -o out/prandtl_k10 --set k=10
--   moraine examples/prandtl_footing/deck.lua -o out/prandtl_rough --set rough=true
--   moraine examples/prandtl_footing/deck.lua -o out/prandtl_fbar --set volumetric=fbar
--   python3 examples/prandtl_footing/plot.py out/prandtl out/prandtl/load_settlement.png
--
-- Parameters: k (5), travel (1e-3 m), rough (false), material (von_mises),
-- boundary (wls), nu (0.333), volumetric (standard; fbar averages the
-- divergence over the nodes against volumetric locking), tag (footing: the
-- names of the files written), vtk (true), quick (false: k = 3, 0.4 mm, no
-- VTK). Returns a table of the results.
local quick = mpm.param("quick", false)
local k = math.tointeger(mpm.param("k", quick and 3 or 5))
local travel = tonumber(mpm.param("travel", quick and 4e-4 or 1e-3))
local rough = mpm.param("rough", false)
local material = mpm.param("material", "von_mises")
local tag = mpm.param("tag", "footing")
local vtk = mpm.param("vtk", not quick)
local volumetric = mpm.param("volumetric", "standard")
local E, nu, rho, c = 1e9, tonumber(mpm.param("nu", 0.333)), 1000, 10e3
local B, L = 1.0, 5.0
local h = B / (2 * k + 1)
local V, ramp = 4e-3, 0.02
local qu = (2 + math.pi) * c

local soil
if material == "mohr_coulomb" then
  soil = mpm.material.mohr_coulomb{ density = rho, E = E, nu = nu, phi = 0, psi = 0, cohesion = c }
else
  assert(material == "von_mises", "material: expected von_mises or mohr_coulomb")
  soil = mpm.material.von_mises{ density = rho, E = E, nu = nu, yield = math.sqrt(3) * c }
end
local sim = mpm.simulation{ dim = 2, grid = { size = { L, L }, cell = h }, shape = "quadratic_bspline",
  shape_boundary = mpm.param("boundary", "wls"), scheme = { transfer = "TPIC", stress_update = "USF", volumetric = volumetric },
  boundary = { left = "slip", right = "slip", bottom = "fixed", top = "free" }, dt = { cfl = 1.0 },
  thermo = 0, progress = false, diagnostics = tag .. "_diagnostics.csv", series = false,
  output = vtk and { vtk = tag, every = travel / V / 4, fields = { "displacement", "stress", "eps_D" } } or nil }
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L, L } }, { material = soil, per_axis = 2 })
sim:particle_field{ name = "y0", unit = "m" } -- where each particle started
sim:set_field("y0", function(_, y) return y end)
local function speed(t) return t < ramp and V * 0.5 * (1 - math.cos(math.pi * t / ramp)) or V end
sim:add_wall{ name = "footing", shape = "box", min = { -2 * h, L }, max = { B / 2, L + 0.5 },
              kind = rough and "fixed" or "slip", velocity = function(t) return { 0, -speed(t) } end }

local y0 = sim:wall("footing").pivot[2]
local curve, ek_ratio = {}, 0
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() == 0 then return end
  local w = s:wall("footing")
  curve[#curve + 1] = { y0 - w.pivot[2], w.force[2] / (B / 2) }
  if curve[#curve][1] > 0.5 * travel and s:step() % 10 == 0 then -- the soil under the footing yields
    local e = s:energy()
    ek_ratio = math.max(ek_ratio, e.kinetic / -e.plastic)
  end
end }
sim:run{ time = travel / V + ramp / 2 } -- the footing has then moved `travel`

-- the mean pressure over the last tenth of the settlement s
local function pressure_at(s)
  local sum, n = 0, 0
  for _, p in ipairs(curve) do
    if p[1] >= 0.9 * s and p[1] <= s * (1 + 1e-9) then sum, n = sum + p[2], n + 1 end
  end
  return sum / n
end
-- the reaction per metre over the ten steps before the last: run{time}
-- shortens the last step, and the wall's force in a shortened step is not
-- comparable (its holds at the nodes do not shrink with dt)
local function reaction()
  local sum = 0
  for i = #curve - 10, #curve - 1 do sum = sum + curve[i][2] end
  return sum / 10 * B / 2
end
-- sigma_yy integrated across the whole width at depth d below the surface
-- (particles of a band 2h high): with no gravity and slip sides it carries
-- the footing's load at every depth
local function section_force(d)
  local stress = sim:field("stress")
  local volume, y0, u = sim:field("volume"), sim:field("y0"), sim:field("displacement")
  local sum = 0
  for i = 1, #volume do
    if math.abs(y0[i] + u[3 * i - 1] - (L - d)) < h then sum = sum + stress[6 * (i - 1) + 2] * volume[i] end
  end
  return -sum / (2 * h)
end

local f = assert(io.open(mpm.outdir .. "/" .. tag .. ".csv", "w"))
f:write("settlement_m,settlement_over_B,pressure_Pa,q_over_c,q_over_qu\n")
for _, p in ipairs(curve) do
  f:write(string.format("%.9g,%.9g,%.9g,%.6f,%.6f\n", p[1], p[1] / B, p[2], p[2] / c, p[2] / qu))
end
f:close()
local e = sim:energy()
local r = { k = k, h = h, B = B, c = c, qu = qu, travel = travel, curve = curve, steps = sim:step(),
            particles = sim:particle_count(), q_04 = pressure_at(math.min(4e-4, travel)), q_end = pressure_at(travel),
            force = reaction(), section = section_force(B), kinetic = e.kinetic,
            plastic = -e.plastic, wall_work = e.walls, ek_ratio = ek_ratio }
print(string.format("footing %s %s, h = B/%d (%d particles, %d steps): q/q_u = %.4f at s/B = %.1e, %.4f at %.1e",
                    rough and "rough" or "smooth", material, 2 * k + 1, r.particles, r.steps, r.q_04 / qu,
                    math.min(4e-4, travel) / B, r.q_end / qu, travel / B))
print(string.format("  reaction %.1f N/m (mean of ten steps), sigma_yy across the width at depth B %.1f N/m;"
                    .. " E_k %.3g J/m = %.2g of the plastic work %.3g J/m (at most %.2g over the second half)",
                    r.force, r.section, e.kinetic, e.kinetic / -e.plastic, -e.plastic, ek_ratio))
return r
