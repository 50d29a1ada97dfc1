-- moraine test decks: small assertion helpers. A failed check raises an
-- error, so moraine exits non-zero with the deck file and line.
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

function T.done(name)
  print(string.format("%s: %d checks passed", name or "deck", T.checks))
end

return T
