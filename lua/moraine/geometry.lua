-- moraine.geometry: shapes and grids that decks otherwise work out by hand.
--
--   local geometry = require "moraine.geometry"
--   local slope = geometry.slope{ height = 5, angle = 30, crest = 5, toe = 5, base = 2 }
--   local grid = geometry.grid_around{ region_min = { 0, 0 }, region_max = { 23.66, 7 }, cell = 0.25,
--                                      pad = { 0, 2, 0, 3 } }
--   local sim = mpm.simulation{ dim = 2, grid = grid, ... }
--   sim:add_particles(slope, { material = soil })
local mpm = rawget(_G, "mpm") or require "moraine"

local M = {}

local function number(t, key, where, default, check)
  local v = t[key]
  if v == nil then v = default end
  if type(v) ~= "number" or v ~= v then error(string.format("%s: %s must be a number", where, key), 3) end
  if check and not check(v) then error(string.format("%s: %s = %g is out of range", where, key, v), 3) end
  return v
end

--- A 2D slope on a foundation layer, as an mpm.polygon region: a foundation
-- `base` m deep and `toe + run + crest` m long, the slope rising `height` m at
-- `angle` degrees (90: a vertical cut) over the run height / tan(angle), with `toe` m of flat
-- ground in front and `crest` m behind. The lower left corner is at `origin`
-- (default {0, 0}); the slope faces -x. Returns the region and a table of
-- its key points {toe = {x, y}, crest = {x, y}, width, height}.
function M.slope(t)
  local where = "geometry.slope{}"
  if type(t) ~= "table" then error(where .. ": expected a table of options", 2) end
  local positive = function(v) return v > 0 end
  local H = number(t, "height", where, nil, positive)
  local angle = number(t, "angle", where, nil, function(v) return v > 0 and v <= 90 end)
  local crest = number(t, "crest", where, 0, function(v) return v >= 0 end)
  local toe = number(t, "toe", where, 0, function(v) return v >= 0 end)
  local base = number(t, "base", where, 0, function(v) return v >= 0 end)
  local o = t.origin or { 0, 0 }
  local run = angle == 90 and 0 or H / math.tan(math.rad(angle)) -- 90: a vertical cut
  local x0, y0 = o[1], o[2]
  local xt, xc = x0 + toe, x0 + toe + run
  local width = toe + run + crest
  -- counter-clockwise from the lower left corner; corners that coincide
  -- (no foundation, no toe, no crest) are listed once
  local outline = { { x0, y0 }, { x0 + width, y0 }, { x0 + width, y0 + base + H }, { xc, y0 + base + H },
                    { xt, y0 + base }, { x0, y0 + base } }
  local v = {}
  for _, p in ipairs(outline) do
    local last = v[#v]
    if not last or last[1] ~= p[1] or last[2] ~= p[2] then v[#v + 1] = p end
  end
  if v[#v][1] == v[1][1] and v[#v][2] == v[1][2] then v[#v] = nil end
  return mpm.polygon{ vertices = v }, { toe = { xt, y0 + base }, crest = { xc, y0 + base + H }, width = width,
                                        height = base + H }
end

--- The grid table {origin, size, cell} that holds the box region_min ..
-- region_max with `pad` cells of margin on each side ({left, right, bottom,
-- top} in 2D, {left, right, bottom, top, back, front} in 3D, or one number
-- for every side; default 2, the support of quadratic and cubic B-splines
-- beyond the material), its nodes aligned with region_min so that the body's
-- faces lie on cell faces when its extent is a whole number of cells.
function M.grid_around(t)
  local where = "geometry.grid_around{}"
  if type(t) ~= "table" then error(where .. ": expected a table of options", 2) end
  local lo, hi = t.region_min, t.region_max
  if type(lo) ~= "table" or type(hi) ~= "table" or #lo ~= #hi or #lo < 2 or #lo > 3 then
    error(where .. ": region_min and region_max must be points of 2 or 3 numbers", 2)
  end
  local h = number(t, "cell", where, nil, function(v) return v > 0 end)
  local dim = #lo
  local pad = t.pad or 2
  if type(pad) == "number" then
    local p = {}
    for k = 1, 2 * dim do p[k] = pad end
    pad = p
  end
  if #pad ~= 2 * dim then error(string.format("%s: pad must list %d numbers (or be one number)", where, 2 * dim), 2) end
  local origin, size = {}, {}
  for d = 1, dim do
    if not (hi[d] > lo[d]) then error(string.format("%s: region_max[%d] must be above region_min[%d]", where, d, d), 2) end
    local below, above = pad[2 * d - 1], pad[2 * d]
    if below < 0 or above < 0 or below ~= math.floor(below) or above ~= math.floor(above) then
      error(string.format("%s: pad must be whole numbers of cells >= 0", where), 2)
    end
    local cells = math.ceil((hi[d] - lo[d]) / h - 1e-9)
    origin[d] = lo[d] - below * h
    size[d] = (cells + below + above) * h
  end
  return { origin = origin, size = size, cell = h }
end

return M
