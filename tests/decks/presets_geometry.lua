-- The pure-Lua helpers moraine.presets and moraine.geometry:
--  - every preset builds its material, and the material reads back each
--    parameter of the set, an override replacing one of them;
--  - an unknown set and a bad override are refused with the name;
--  - geometry.slope: particles seeded into the slope region carry the mass
--    density x area of its outline (foundation + slope + crest) within the
--    seeding's discretisation (half a cell along the inclined face), and the
--    region's key points are where the outline puts them;
--  - geometry.grid_around: the grid holds the body with the asked margin,
--    its nodes on the body's lower corner.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local presets = require "moraine.presets"
local geometry = require "moraine.geometry"

for _, name in ipairs(presets.names()) do
  local p = presets.parameters(name)
  local m = presets.material(name)
  T.check(m.model == p.model, "%s: model %s, expected %s", name, m.model, p.model)
  for k, v in pairs(p) do
    if type(v) == "number" then T.close(m[k], v, 1e-15, name .. "." .. k) end
  end
end
T.check(presets.material("camargue_sand", { phi = 30 }).phi == 30, "override of phi")
T.check(presets.parameters("water").viscosity == 1.01e-3, "water viscosity (002 §5.4)")
local ok, msg = pcall(presets.material, "sandd")
T.check(not ok and msg:find("unknown set 'sandd'") and msg:find("camargue_sand"), "unknown set: %s", tostring(msg))
ok, msg = pcall(presets.material, "water", { viscosity = -1 })
T.check(not ok and msg:find("presets.material%('water'%)") and msg:find("viscosity"), "bad override: %s", tostring(msg))

-- slope: 2 m foundation, 4 m high at 45 degrees, 3 m toe, 2 m crest
local H, base, toe, crest, h = 4, 2, 3, 2, 0.1
local slope, key = geometry.slope{ height = H, angle = 45, crest = crest, toe = toe, base = base, origin = { 1, 0 } }
local width = toe + H + crest
T.close(key.width, width, 1e-15, "slope width")
T.close(key.toe[1], 1 + toe, 1e-15, "toe x")
T.close(key.crest[1], 1 + toe + H, 1e-15, "crest x")
T.close(key.crest[2], base + H, 1e-15, "crest y")
local grid = geometry.grid_around{ region_min = { 1, 0 }, region_max = { 1 + width, base + H }, cell = h, pad = { 2, 3, 0, 1 } }
T.close(grid.origin[1], 1 - 2 * h, 1e-12, "grid origin x")
T.close(grid.origin[2], 0, 1e-12, "grid origin y")
T.close(grid.size[1], width + 5 * h, 1e-12, "grid width")
T.close(grid.size[2], base + H + h, 1e-12, "grid height")
local rho = presets.parameters("footing_clay").density
local sim = mpm.simulation{ dim = 2, grid = grid, thermo = 0, diagnostics = false }
sim:add_particles(slope, { material = presets.material("footing_clay"), per_axis = 2 })
local area = width * base + crest * H + 0.5 * H * H
local mass = sim:diagnostics().mass
T.close(mass, rho * area, 0.5 * h * H * math.sqrt(2) / area, "mass of the seeded slope against density x area")
print(string.format("presets_geometry: %d presets; slope area %.4f m^2, seeded %.4f m^2 (%.2f %%)", #presets.names(),
                    area, mass / rho, 100 * (mass / rho - area) / area))
ok, msg = pcall(geometry.slope, { height = 4, angle = 0 })
T.check(not ok and msg:find("angle = 0 is out of range"), "angle 0: %s", tostring(msg))
local cut, cut_key = geometry.slope{ height = 4, angle = 90, crest = 2, toe = 1 }
T.check(cut:contains(2.9, 3.9) and not cut:contains(0.9, 0.1) and cut_key.crest[1] == 1, "vertical cut outline")
ok, msg = pcall(geometry.grid_around, { region_min = { 0, 0 }, region_max = { 1, 1 }, cell = 0.1, pad = { 1, 2 } })
T.check(not ok and msg:find("pad must list 4 numbers"), "pad: %s", tostring(msg))
T.done("presets_geometry")
