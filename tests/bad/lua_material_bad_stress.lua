-- expect: lua_material_bad_stress\.lua:5: material 'lua' \(lua\): the update function left stress\[1\]\[2\] not a number, expected a number
-- case: runtime | a Lua material's update function that leaves a stress component that is not a number
local mpm = require "moraine"
local mat = mpm.material.lua{ density = 1000, wave_speed = 40,
  update = function(b)
    for i = 1, b.n do b.stress[i][2] = "soft" end
  end }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 2 }
