-- expect: missing_dim\.lua:4: simulation\{\}: missing required key 'dim' \(dimension: 2 \(plane strain\) or 3\)
-- case: keys | a simulation without dim
local mpm = require "moraine"
local sim = mpm.simulation{ grid = { size = {1, 1}, cell = 0.1 } }
