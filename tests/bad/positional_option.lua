-- expect: positional_option\.lua:4: simulation\{\}: options must be named \(key = value\); found a positional value
-- case: keys | a value without a key in an option table
local mpm = require "moraine"
local sim = mpm.simulation{ 2, grid = { size = {1, 1}, cell = 0.1 } }
