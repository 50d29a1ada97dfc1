-- expect: negative_viscosity\.lua:4: material\.newtonian\{\}: viscosity = -1 is out of range \(expected a value >= 0\)
-- case: ranges | negative viscosity
local mpm = require "moraine"
local mat = mpm.material.newtonian{ density = 1000, viscosity = -1, sound_speed = 10 }
