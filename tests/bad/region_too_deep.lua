-- expect: region_too_deep\.lua:7: union\(\): region: the combination would nest regions 1001 levels deep, more than the limit of 1000 \(combine many regions in one call rather than one at a time\)
-- case: geometry | a region combined one box at a time past the nesting limit of 1000 levels
local mpm = require "moraine"
-- a chain r = r + box nests one level per addition; mpm.union(r1, ..., rn) would not
local r = mpm.box{ min = { 0, 0 }, max = { 0.01, 0.01 } }
for i = 1, 1000 do
  r = r + mpm.box{ min = { 0, 0 }, max = { 0.01 * (i % 50 + 1), 0.01 } }
end
