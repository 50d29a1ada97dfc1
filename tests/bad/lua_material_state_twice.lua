-- expect: lua_material_state_twice\.lua:4: material\.lua\{\}: state\[2\] = 'eps' is given twice
-- case: keys | a Lua material declaring the same history variable twice
local mpm = require "moraine"
local mat = mpm.material.lua{ density = 1000, wave_speed = 40, state = { "eps", "eps" }, update = function(b) end }
