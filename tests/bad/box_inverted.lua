-- expect: box_inverted\.lua:4: box\{\}: box: min\[1\] = 0\.5 is not below max\[1\] = 0\.2
-- case: geometry | a box whose min is above its max
local mpm = require "moraine"
local b = mpm.box{ min = {0.5, 0.5}, max = {0.2, 0.2} }
