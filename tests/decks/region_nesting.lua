-- Combining many regions in one call nests them as a balanced tree (about
-- log2(n) levels, under the limit of 1000, MRN_REGION_MAX_DEPTH), with the
-- same point set as combining them one at a time:
--  * mpm.union of 5000 disks along a line: inside at every disk centre,
--    outside between them;
--  * 500 disks seeded from their union in one call and from a chain
--    r = r + disk (500 levels deep) give the same particles;
--  * mpm.difference(a, b, c, ...) removes every later region from the first;
--  * mpm.intersection of 3000 boxes is their common part.
local T = dofile(mpm.deck_dir .. "/testlib.lua")

local n, spacing, radius = 5000, 2e-4, 5e-5
local disks = {}
for i = 1, n do disks[i] = mpm.disk{ center = { i * spacing, 0.5 }, radius = radius } end
local many = mpm.union(table.unpack(disks))
for _, i in ipairs{ 1, 2, 1234, 2500, 4999, 5000 } do
  T.check(many:contains(i * spacing, 0.5), "the union misses disk %d", i)
  T.check(not many:contains((i + 0.5) * spacing, 0.5), "the union holds the gap after disk %d", i)
end

-- seeding: a one-at-a-time chain of 500 disks and the balanced union of the same
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local function seeded(region)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.2, 1 }, cell = 0.01 }, thermo = 0, diagnostics = false,
                              series = false }
  return sim:add_particles(region, { material = mat, per_axis = 8 }), sim
end
local beads = {}
for i = 1, 500 do beads[i] = mpm.disk{ center = { i * 0.002, 0.5 }, radius = 0.0008 } end
local chain = beads[1]
for i = 2, 500 do chain = chain + beads[i] end
local count_chain, sim_chain = seeded(chain)
local count_union, sim_union = seeded(mpm.union(table.unpack(beads)))
T.check(count_chain > 0 and count_chain == count_union, "seeded %d particles from the chain, %d from the balanced union",
        count_chain, count_union)
for _, i in ipairs{ 1, count_union // 2, count_union } do
  local a, b = sim_chain:particle(i).x, sim_union:particle(i).x
  T.check(a[1] == b[1] and a[2] == b[2], "particle %d at (%g, %g) from the chain, (%g, %g) from the union", i, a[1], a[2],
          b[1], b[2])
end

-- difference of many: the first region without any of the others
local bar = mpm.box{ min = { 0, 0.4 }, max = { 1.1, 0.6 } }
local holes = mpm.difference(bar, table.unpack(disks))
T.check(not holes:contains(1234 * spacing, 0.5), "the difference keeps a removed disk")
T.check(holes:contains(1234.5 * spacing, 0.5), "the difference lost the gap between two disks")
T.check(holes:contains(0.5, 0.45), "the difference lost the bar outside the disks")

-- intersection of many: the common part of nested boxes
local boxes = {}
for i = 1, 3000 do boxes[i] = mpm.box{ min = { -i * 1e-4, -i * 1e-4 }, max = { 1 + i * 1e-4, 1 } } end
local common = mpm.intersection(table.unpack(boxes))
T.check(common:contains(0.5, 0.5) and not common:contains(-1.5e-4, 0.5), "the intersection of 3000 boxes is not the first")
T.done("region_nesting")
