-- expect: negative_radius\.lua:4: disk\{\}: radius = -0\.1 is out of range \(expected a value > 0, in m\)
-- case: geometry | a disk with a negative radius
local mpm = require "moraine"
local d = mpm.disk{ center = {0.5, 0.5}, radius = -0.1 }
