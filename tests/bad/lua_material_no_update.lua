-- expect: lua_material_no_update\.lua:4: material\.lua\{\}: .*update
-- case: keys | a Lua material without its update function
local mpm = require "moraine"
local mat = mpm.material.lua{ density = 1000, wave_speed = 40 }
