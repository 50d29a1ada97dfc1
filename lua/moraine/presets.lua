-- moraine.presets: the material parameter sets of the verification cases
-- (000, 001, 002), by name, so that a deck says which set it uses instead of
-- copying numbers:
--
--   local presets = require "moraine.presets"
--   local sand = presets.material("camargue_sand")                 -- 000 Table 2
--   local loose = presets.material("camargue_sand", { phi = 30 })  -- one value changed
--   local p = presets.parameters("water")                          -- the numbers only
--
-- Every set names its constitutive model (a key of mpm.material) and its
-- source; units are SI (kg/m^3, Pa, degrees for angles, Pa s, m/s).
local mpm = rawget(_G, "mpm") or require "moraine"

local M = {}

-- copper of the Taylor bar is given by its bulk and shear moduli (001 Table 5)
local K_cu, G_cu = 130e9, 43.3e9

M.sets = {
  camargue_sand = { model = "mohr_coulomb", source = "000 Table 2 (granular column collapse)",
                    density = 1748, E = 1.284e7, nu = 0.16, phi = 33.75, psi = 0, cohesion = 1, tension = -1 },
  camargue_sand_elastic = { model = "linear_elastic", source = "000 §5.1 (the settling phase of the collapse)",
                            density = 1748, E = 1.284e7, nu = 0.16 },
  sand_column = { model = "drucker_prager", source = "002 §5.5 (sand column collapse)",
                  density = 1400, E = 10e6, nu = 0.3, phi = 35, psi = 0, cohesion = 0 },
  footing_clay = { model = "von_mises", source = "002 §5.2 (strip footing; c = 10 kPa, yield = sqrt(3) c in plane strain)",
                   density = 1000, E = 1e9, nu = 0.333, yield = math.sqrt(3) * 10e3 },
  water = { model = "newtonian", source = "002 §5.4 (dam break; Morris's equation of state, Eq. 70)",
            density = 1000, viscosity = 1.01e-3, sound_speed = 50 },
  copper = { model = "von_mises", source = "001 §7.4 Table 5 (Taylor bar; K = 130 GPa, G = 43.3 GPa)",
             density = 8930, E = 9 * K_cu * G_cu / (3 * K_cu + G_cu),
             nu = (3 * K_cu - 2 * G_cu) / (2 * (3 * K_cu + G_cu)), yield = 0.4e9, hardening = 0.1e9 },
  cantilever_beam = { model = "hencky", source = "001 §7.1 Table 3 (elastic cantilever)",
                      density = 7750e3, E = 1e9, nu = 0.2 },
  soft_cylinders = { model = "hencky", source = "001 §7.2 (colliding elastic cylinders)",
                     density = 5, E = 100, nu = 0.3 },
}

local function known()
  local names = {}
  for name in pairs(M.sets) do names[#names + 1] = name end
  table.sort(names)
  return names
end

--- the names of every set, sorted
function M.names() return known() end

local function copy(name, overrides, level)
  local set = M.sets[name]
  if not set then
    error(string.format("presets: unknown set '%s' (known: %s)", tostring(name), table.concat(known(), ", ")), level + 1)
  end
  local p = {}
  for k, v in pairs(set) do p[k] = v end
  for k, v in pairs(overrides or {}) do p[k] = v end
  return p
end

--- A copy of set `name`'s parameters (with `model` and `source`), the keys
-- of `overrides` replacing or adding values.
function M.parameters(name, overrides) return copy(name, overrides, 2) end

--- The material of set `name` (mpm.material.<model>{...}), with the keys of
-- `overrides` replacing or adding parameters (any key of that model, `name`
-- included); the model's own checks apply to the result.
function M.material(name, overrides)
  local p = copy(name, overrides, 2)
  local model = p.model
  p.model, p.source = nil, nil
  -- the model's message, raised at the caller's line rather than this file's
  local ok, result = pcall(mpm.material[model], p)
  if not ok then error(string.format("presets.material('%s'): %s", name, (tostring(result):gsub("^[^:]*:%d+: ", ""))), 2) end
  return result
end

return M
