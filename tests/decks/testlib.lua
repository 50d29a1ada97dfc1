-- moraine test decks: small assertion helpers. A failed check raises an
-- error, so moraine exits non-zero with the deck file and line.
local results = require "moraine.results"
local T = { checks = 0 }

local function fail(level, fmt, ...)
  error(string.format(fmt, ...), level + 1)
end

--- |a - b| <= rtol * |b| (plus atol)
function T.close(a, b, rtol, what, atol)
  T.checks = T.checks + 1
  atol = atol or 0
  if not (math.abs(a - b) <= rtol * math.abs(b) + atol) then
    fail(2, "%s: got %.12g, expected %.12g (relative error %.3g > %.3g)", what or "value", a, b,
         math.abs(a - b) / math.max(math.abs(b), 1e-300), rtol)
  end
  return math.abs(a - b) / math.max(math.abs(b), 1e-300)
end

function T.check(cond, fmt, ...)
  T.checks = T.checks + 1
  if not cond then fail(2, fmt or "check failed", ...) end
end

--- T.expect{ id, what, value, reference, rtol, atol, max, min, unit, asserted, ... }:
-- records the figure as a RESULT line (lua/moraine/results.lua, read by the
-- validation report) and, unless asserted = false, fails the deck when a
-- tolerance or bound does not hold. Returns the relative error (or nil).
function T.expect(t)
  local r = results.record(t)
  if r.asserted and r.status ~= "reported" then T.checks = T.checks + 1 end
  if r.status == "fail" then
    local limits = {}
    if t.rtol or t.atol then
      limits[#limits + 1] = string.format("expected %.12g within rtol %.3g%s", t.reference, t.rtol or 0,
                                          t.atol and string.format(" + atol %.3g", t.atol) or "")
    end
    if t.max then limits[#limits + 1] = string.format("at most %.12g", t.max) end
    if t.min then limits[#limits + 1] = string.format("at least %.12g", t.min) end
    fail(2, "%s: got %.12g, %s", t.what or t.id, t.value, table.concat(limits, ", "))
  end
  return r.error
end

--- the items of a comma- or space-separated list, e.g. a --set option
function T.list(s)
  local t = {}
  for item in s:gmatch("[^,%s]+") do t[#t + 1] = item end
  return t
end

--- a strategy of a deck's list as a transfer preset and the scheme's holds:
--- "FLIP" -> "FLIP", "grid"; "FLIP/particles" -> "FLIP", "particles"
function T.strategy(name)
  return name:match("^[^/]+"), name:match("/(.+)$") or "grid"
end

--- the least-squares slope of ys against xs (lists of equal length, >= 2)
function T.slope(xs, ys)
  local n, sx, sy, sxx, sxy = #xs, 0, 0, 0, 0
  for i = 1, n do
    sx, sy, sxx, sxy = sx + xs[i], sy + ys[i], sxx + xs[i] * xs[i], sxy + xs[i] * ys[i]
  end
  return (n * sxy - sx * sy) / (n * sxx - sx * sx)
end

--- index of the particle nearest the point x (2 or 3 numbers)
function T.nearest(sim, x)
  local best, index = math.huge, nil
  for i = 1, sim:particle_count() do
    local p, d = sim:particle(i).x, 0
    for k = 1, #x do d = d + (p[k] - x[k]) ^ 2 end
    if d < best then best, index = d, i end
  end
  return index
end

--- run the example deck at `path` (relative to tests/decks) as if given
--- --set NAME=VALUE for each entry of `set`; returns what the deck returns.
--- mpm.param is restored, and the deck's error raised, as it was.
function T.run_example(path, set)
  local param = mpm.param
  mpm.param = function(name, default)
    if set[name] ~= nil then return set[name] end
    return param(name, default)
  end
  local ok, r = pcall(dofile, mpm.deck_dir .. "/" .. path)
  mpm.param = param
  if not ok then error(r, 0) end
  return r
end

function T.done(name)
  print(string.format("%s: %d checks passed", name or "deck", T.checks))
end

return T
