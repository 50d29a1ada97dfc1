-- Registered per-particle fields and grid probes from Lua.
--  * fields: values set per particle, as a table and from a function read back
--    unchanged; a checkpoint restores them (mpm.load); output{ fields } writes
--    only what it lists; misuse is refused with a message.
--  * probes: a block translating rigidly at v (no gravity, no stress) has the
--    nodal velocity v at every node it reaches, so the interpolated velocity
--    inside it is v to round-off (the shape functions sum to 1, 002 Eq. 38);
--    the probed momentum is the probed mass times v; outside the grid: nil;
--    a block falling freely (gravity only, no stress) has the nodal
--    acceleration g (000, Eq. 28 with f = 0), which the probe works out as
--    (velocity_new - velocity) / dt.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }

local function refused(pattern, fn, ...)
  local ok, err = pcall(fn, ...)
  T.check(not ok and tostring(err):find(pattern), "expected an error matching '%s', got %s", pattern, tostring(err))
end

for _, dim in ipairs{ 2, 3 } do
  local v = dim == 2 and { 0.3, -0.2 } or { 0.3, -0.2, 0.1 }
  local lo, hi = { 0.3, 0.3, 0.3 }, { 0.7, 0.7, 0.7 }
  if dim == 2 then lo[3], hi[3] = nil, nil end
  local sim = mpm.simulation{ dim = dim, grid = { size = dim == 2 and { 1, 1 } or { 1, 1, 1 }, cell = 0.1 },
                              thermo = 0, diagnostics = false, series = false,
                              output = { vtk = "p" .. dim, every_steps = 5, fields = { "id", "damage" } } }
  sim:add_particles(mpm.box{ min = lo, max = hi }, { material = mat, velocity = v })
  local n = sim:particle_count()
  sim:particle_field{ name = "damage", init = 0.25, unit = "1" }
  sim:particle_field{ name = "tag", components = 2 }
  T.check(sim:value("damage", n) == 0.25, "init value")
  sim:set_field("tag", function(x, y, z, i) return i, -i end)
  local flat = {}
  for i = 1, n do flat[i] = i * 0.5 end
  sim:set_field("damage", flat)
  sim:set_value("tag", 2, { 20, 21 })
  local d, nc = sim:field("damage")
  T.check(nc == 1 and #d == n and d[n] == n * 0.5, "damage read back")
  local tg, nt = sim:field("tag")
  T.check(nt == 2 and tg[3] == 20 and tg[4] == 21 and tg[2 * n] == -n, "tag read back")
  T.check(sim:reduce("sum", "damage") == 0.5 * n * (n + 1) / 2, "reduce over a registered field")

  refused("already registered", sim.particle_field, sim, { name = "damage" })
  refused("built%-in particle field", sim.particle_field, sim, { name = "velocity" })
  refused("must be 1 to 31 letters", sim.particle_field, sim, { name = "2d" })
  refused("built%-in field, which a deck cannot set", sim.set_value, sim, "mass", 1, 2)
  refused("did you mean 'damage'", sim.set_value, sim, "damag", 1, 2)
  refused("needs " .. n .. " values", sim.set_field, sim, "damage", { 1, 2 })
  refused("takes a table of 2 numbers", sim.set_value, sim, "tag", 1, 5)
  refused("outside 1%.%." .. n, sim.value, sim, "damage", n + 1)

  sim:run{ steps = 5 }
  local c = dim == 2 and { x = 0.5, y = 0.5 } or { x = 0.5, y = 0.5, z = 0.5 }
  c.field = "velocity"
  local pv = sim:probe(c)
  for k = 1, dim do T.close(pv[k], v[k], 1e-12, "probed velocity component " .. k) end
  c.field = "mass"
  local m = sim:probe(c)
  T.check(m > 0, "probed mass %g", m)
  c.field = "momentum"
  local pm = sim:probe(c)
  for k = 1, dim do T.close(pm[k], m * v[k], 1e-12, "probed momentum component " .. k) end
  T.check(sim:probe{ field = "force", x = 1.5, y = 0.5, z = dim == 3 and 0.5 or nil } == nil, "outside: nil")
  local g = dim == 2 and { 0, -9.81 } or { 0, 0, -9.81 }
  local fall = mpm.simulation{ dim = dim, grid = { size = dim == 2 and { 1, 1 } or { 1, 1, 1 }, cell = 0.1 },
                               gravity = g, thermo = 0, diagnostics = false, series = false }
  fall:add_particles(mpm.box{ min = lo, max = hi }, { material = mat })
  fall:run{ steps = 3 }
  c.field = "acceleration"
  local pa = fall:probe(c)
  for k = 1, dim do T.close(pa[k], g[k], 1e-9, "probed acceleration component " .. k, 1e-9 * 9.81) end
  if dim == 2 then refused("z is only for a 3D simulation", sim.probe, sim, { field = "mass", x = 0.5, y = 0.5, z = 0 })
  else refused("z is required in 3D", sim.probe, sim, { field = "mass", x = 0.5, y = 0.5 }) end

  -- field(name, {gather = true}): every particle's values in the order of the ids
  -- (in a run on one process, this process's particles sorted by id), after a
  -- reordering by block (sort_every) has put them out of id order
  local sorted = mpm.simulation{ dim = dim, grid = { size = dim == 2 and { 1, 1 } or { 1, 1, 1 }, cell = 0.1 },
                                 thermo = 0, diagnostics = false, sort_every = 1 }
  local left_hi, right_lo = { table.unpack(hi) }, { table.unpack(lo) }
  left_hi[1], right_lo[1] = 0.45, 0.55
  sorted:add_particles(mpm.box{ min = right_lo, max = hi }, { material = mat, velocity = v })
  sorted:add_particles(mpm.box{ min = lo, max = left_hi }, { material = mat, velocity = v })
  sorted:run{ steps = 2 }
  local ids, vel = sorted:field("id"), sorted:field("velocity")
  local gids = sorted:field("id", { gather = true })
  local gvel, gnc = sorted:field("velocity", { gather = true })
  n = sorted:particle_count()
  T.check(#gids == n and gnc == 3 and #gvel == 3 * n, "gather: %d ids, %d values", #gids, #gvel)
  local at = {}
  for i = 1, n do at[ids[i]] = i end
  local moved = 0
  for k = 1, n do
    T.check(k == 1 or gids[k] > gids[k - 1], "gather: ids out of order at %d", k)
    local i = at[gids[k]]
    if i ~= k then moved = moved + 1 end
    for c = 1, 3 do T.check(gvel[3 * (k - 1) + c] == vel[3 * (i - 1) + c], "gather: velocity of id %d", gids[k]) end
  end
  T.check(moved > 0, "the sort did not reorder the particles, so the gather's order is not tested")
  refused("gathr", sorted.field, sorted, "mass", { gathr = true })
  sorted:free()
  n = sim:particle_count()

  -- a checkpoint holds the registered fields; mpm.load brings them back
  sim:save("fields" .. dim .. ".h5")
  local loaded = mpm.load("fields" .. dim .. ".h5", { thermo = 0, diagnostics = false })
  local d2 = loaded:field("damage")
  local t2 = loaded:field("tag")
  local d1, t1 = sim:field("damage"), sim:field("tag")
  for i = 1, n do T.check(d2[i] == d1[i], "loaded damage %d", i) end
  for i = 1, 2 * n do T.check(t2[i] == t1[i], "loaded tag %d", i) end
  loaded:particle_field{ name = "extra" } -- a loaded simulation registers more
  T.check(loaded:value("extra", 1) == 0, "new field on a loaded simulation")
end
T.done("particle_fields")
