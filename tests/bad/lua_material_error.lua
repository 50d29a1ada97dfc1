-- expect: lua_material_error\.lua:6: the law fails \(in the update function of material 'broken', .*lua_material_error\.lua:5\)
-- case: runtime | an error raised in the update function of a Lua material
local mpm = require "moraine"
local mat = mpm.material.lua{ name = "broken", density = 1000, wave_speed = 40,
  update = function(b)
    if b.n > 0 then error("the law fails") end
  end }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false, series = false }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:run{ steps = 2 }
