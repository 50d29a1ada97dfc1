-- Two elastic disks collide head-on (Sulsky, Chen and Schreyer 1994; 000
-- App. B): a unit square of 20 x 20 cells, disks of radius 0.2 m at
-- (0.2, 0.2) and (0.8, 0.8) moving towards each other at (0.1, 0.1) m/s,
-- E = 1000 Pa, nu = 0.3, rho = 1000 kg/m^3, dt = 1e-3 s, quadratic
-- B-splines, USF. With contact = true each disk is a body and they meet
-- through frictionless contact (solver/contact.h); with false they share one
-- velocity field, as without bodies. With dim = 3, two balls in the unit
-- cube, centres (0.2, 0.2, 0.2) and (0.8, 0.8, 0.8), velocities
-- +-(0.1, 0.1, 0.1) m/s, run to 4 s (they meet later along the longer
-- diagonal).
-- --set cell=H changes the cell size (0.05 m), --set save=true writes the
-- final state to state.h5, --set compare=true runs the single field too and
-- checks that contact's energy error |E/E0 - 1| is at most compare_factor
-- (1) times its.
--   moraine tests/decks/contact_disks.lua [--set contact=false] [--set transfer=APIC] [--set dim=3]
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local contact = mpm.param("contact", true)
local transfer = mpm.param("transfer", "FLIP")
local dim = mpm.param("dim", 2)
local t_end = mpm.param("time", dim == 3 and 4.0 or 3.0)
local rubber = mpm.material.linear_elastic{ density = 1000, E = 1000, nu = 0.3 }
local h = mpm.param("cell", 0.05)

-- a point or velocity with every component c
local function diagonal(c) return dim == 3 and { c, c, c } or { c, c } end
local region = dim == 3 and mpm.sphere or mpm.disk

local function disks(body_a, body_b)
  local s = mpm.simulation{
    dim = dim, grid = { origin = diagonal(0), size = diagonal(1), cell = h }, shape = "quadratic_bspline",
    boundary = { all = "free" }, scheme = { transfer = transfer, stress_update = mpm.param("stress_update", "USF") },
    dt = { fixed = 1e-3 }, thermo = 0, diagnostics = false,
  }
  s:add_particles(region{ center = diagonal(0.2), radius = 0.2 },
                  { material = rubber, velocity = diagonal(0.1), body = body_a })
  s:add_particles(region{ center = diagonal(0.8), radius = 0.2 },
                  { material = rubber, velocity = diagonal(-0.1), body = body_b })
  return s
end
local sim = disks("a", "b")
if contact then sim:add_contact{ bodies = { "a", "b" }, kind = "frictionless" } end

-- per body: mass, momentum along the line of centres (1, 1)/sqrt 2 (in 3D
-- (1, 1, 1)/sqrt 3), and the extreme positions along it (the front of a,
-- the back of b)
local function bodies()
  local m, b = sim:field("mass"), sim:field("body")
  local r = { { m = 0, p = 0, front = -math.huge }, { m = 0, p = 0, front = math.huge } }
  for i = 1, #m do
    local q = sim:particle(i)
    local s = (q.x[1] + q.x[2] + (dim == 3 and q.x[3] or 0)) / math.sqrt(dim)
    local k = b[i] == 1 and 1 or 2
    r[k].m = r[k].m + m[i]
    r[k].p = r[k].p + m[i] * (q.v[1] + q.v[2] + (dim == 3 and q.v[3] or 0)) / math.sqrt(dim)
    r[k].front = k == 1 and math.max(r[k].front, s) or math.min(r[k].front, s)
  end
  return r
end

local E0, p0 = sim:energy().total, bodies()[1].p
local overlap = -math.huge -- the deepest the front of a got past that of b
sim:hook{ every_steps = mpm.param("verbose", false) and 100 or 10, fn = function()
  local r = bodies()
  overlap = math.max(overlap, r[1].front - r[2].front)
  if mpm.param("verbose", false) then print(sim:time(), r[1].p / r[1].m, r[1].front, r[2].front) end
end }
sim:run{ time = t_end }
-- the state for a comparison between runs (e.g. on 1 and 2 threads)
if mpm.param("save", false) then sim:save("state.h5") end

local d, r = sim:diagnostics(), bodies()
local E = sim:energy().total
local pz = dim == 3 and d.momentum[3] or 0
print(string.format("contact_disks (%dD, %s, %s, contact %s): t = %.2f s, E/E0 = %.4f, W_contact = %.3g %s, "
                    .. "momentum (%.2e, %.2e, %.2e), velocity of a along the line %.4f m/s, deepest overlap %.4f m "
                    .. "(%.2f cells)", dim, transfer, mpm.param("stress_update", "USF"), tostring(contact), sim:time(),
                    E / E0, d.W_contact, dim == 3 and "J" or "J/m", d.momentum[1], d.momentum[2], pz, r[1].p / r[1].m,
                    overlap, overlap / h))
local worst_p = math.max(math.abs(d.momentum[1]), math.abs(d.momentum[2]), math.abs(pz))
T.check(worst_p < 1e-12 * math.abs(p0), "total momentum (%g, %g, %g) is not zero to round-off", d.momentum[1],
        d.momentum[2], pz)
if contact then
  -- they bounced and moved apart: a moves back, a gap between the fronts
  T.check(r[1].p / r[1].m < -0.05, "disk a did not rebound: %g m/s along the line", r[1].p / r[1].m)
  T.check(r[2].front - r[1].front > 0.5 * h, "the disks did not separate: gap %g m", r[2].front - r[1].front)
  T.check(overlap < h, "the disks overlapped by %g m, more than a cell", overlap)
  T.check(E / E0 > mpm.param("energy_min", 0.9), "energy kept E/E0 = %g", E / E0)
end
if contact and mpm.param("compare", false) then
  -- the energy kept, as well as or better than with one field
  local single = disks(nil, nil)
  local E1 = single:energy().total
  single:run{ time = t_end }
  local e_single, e_contact = math.abs(single:energy().total / E1 - 1), math.abs(E / E0 - 1)
  local factor = mpm.param("compare_factor", 1)
  print(string.format("energy error |E/E0 - 1|: contact %.6f, single field %.6f (%.3f times)", e_contact, e_single,
                      e_contact / e_single))
  T.check(e_contact <= factor * e_single, "contact's energy error (%g) is more than %g times one field's (%g)",
          e_contact, factor, e_single)
end
if not contact then
  -- bodies without a contact pair are labels: the same particles, bit for bit, as no bodies at all
  local plain = disks(nil, nil)
  plain:run{ time = t_end }
  for i = 1, sim:particle_count(), 37 do
    local p, q = sim:particle(i), plain:particle(i)
    T.check(p.x[1] == q.x[1] and p.x[2] == q.x[2] and p.v[1] == q.v[1] and p.v[2] == q.v[2],
            "particle %d differs from the run without bodies", i)
  end
end
