-- expect: lua_material_wave_speed\.lua:4: material\.lua\{\}: wave_speed = 0 is out of range
-- case: ranges | a Lua material with a zero wave speed
local mpm = require "moraine"
local mat = mpm.material.lua{ density = 1000, wave_speed = 0, update = function(b) end }
