-- Reordering the particles by grid block (mpm.simulation{ sort_every = N }).
--  * Physics unchanged: a column settling under gravity (USF FLIP, the
--    default scheme) with and without sort_every = 5, compared particle by
--    particle through the id: displacements and stresses agree to 1e-12 of their
--    scale, the total energy to 1e-12 (only the order of the nodal sums
--    changes).
--  * The indices do change (some particle i has an id other than i), the ids
--    stay a permutation of 1..n.
--  * A checkpoint keeps the interval (sim:info().sort_every), and a run
--    restarted from it reorders at the same steps as the straight run: both
--    end bitwise equal, index by index; mpm.load{ sort_every } overrides it.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 2000, E = 5e6, nu = 0.3 }

local function column(sort_every)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 2, 1 }, cell = 0.025 }, gravity = { 0, -9.81 },
                              dt = { fixed = 2e-4 }, thermo = 0, diagnostics = false, series = false,
                              sort_every = sort_every }
  sim:add_particles(mpm.box{ min = { 0.1, 0 }, max = { 1.3, 0.6 } }, { material = mat })
  return sim
end

local plain, sorted = column(nil), column(5)
T.check(plain:info().sort_every == 0 and sorted:info().sort_every == 5, "sort_every in sim:info()")
plain:run{ steps = 40 }
sorted:run{ steps = 40 }

-- the indices changed; the ids are still 1..n
local n = sorted:particle_count()
local ids = sorted:field("id")
local seen, moved = {}, 0
for i = 1, n do
  seen[ids[i]] = true
  if ids[i] ~= i then moved = moved + 1 end
end
for k = 1, n do T.check(seen[k], "id %d missing after the reordering", k) end
T.check(moved > n / 10, "only %d of %d particles changed index", moved, n)

-- the same physics, particle by particle
local at = {}
for i = 1, n do at[ids[i]] = i end
local xp, nx = plain:field("displacement")
local xs = sorted:field("displacement")
local sp, ns = plain:field("stress")
local ss = sorted:field("stress")
local dx, ds, smax = 0, 0, 0
for i = 1, n do -- plain keeps the order of creation: index i is id i
  local j = at[i]
  for d = 1, nx do dx = math.max(dx, math.abs(xp[nx * (i - 1) + d] - xs[nx * (j - 1) + d])) end
  for k = 1, ns do
    ds = math.max(ds, math.abs(sp[ns * (i - 1) + k] - ss[ns * (j - 1) + k]))
    smax = math.max(smax, math.abs(sp[ns * (i - 1) + k]))
  end
end
T.check(dx <= 1e-12 * 1.3, "displacements differ by %g m", dx)
T.check(ds <= 1e-12 * smax, "stresses differ by %g Pa (scale %g)", ds, smax)
T.close(sorted:energy().total, plain:energy().total, 1e-12, "total energy, sorted against plain")

-- a checkpoint at step 40 keeps the interval; straight and restarted runs
-- reorder at steps 40, 45, 50 alike and end bitwise equal
local path = sorted:save("sorted_40.h5")
local resumed = mpm.load(path, { thermo = 0, diagnostics = false })
T.check(resumed:info().sort_every == 5, "sort_every after load: %s", tostring(resumed:info().sort_every))
sorted:run{ steps = 12 }
resumed:run{ steps = 12 }
for _, name in ipairs{ "id", "displacement", "velocity", "stress" } do
  local a, b = sorted:field(name), resumed:field(name)
  for i = 1, #a do T.check(a[i] == b[i], "%s[%d]: straight %.17g, restarted %.17g", name, i, a[i], b[i]) end
end
local off = mpm.load(path, { thermo = 0, diagnostics = false, sort_every = 0 })
T.check(off:info().sort_every == 0, "load{ sort_every = 0 } overrides the saved interval")
print(string.format("sort_every: %d of %d particles moved index; max |dx| %.3g m, max |dsigma| %.3g Pa; %d checks",
                    moved, n, dx, ds, T.checks))
