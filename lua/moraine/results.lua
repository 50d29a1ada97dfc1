-- moraine.results: machine-readable results of a run.
--
--   local results = require "moraine.results"
--   local r = results.record{ id = "lithostatic.sigma_yy", what = "mean sigma_yy at mid-height",
--                             value = s, reference = -rho * g * H / 2, rtol = 0.05, unit = "Pa" }
--
-- record{} prints one line "RESULT {json}" on standard output and returns the
-- record (a table with `status`, `error` and the fields given). Fields:
--   id         unique name of the figure, "<case>.<quantity>"        (required)
--   what       a short description
--   value      moraine's figure (number; required)
--   reference  the reference value (number), optional
--   rtol       tolerance on |value - reference| / |reference|
--   atol       absolute tolerance added to rtol * |reference|
--   max, min   bounds on value (inclusive), instead of or besides a reference
--   unit       unit of value and reference, e.g. "Pa", "%" (text)
--   asserted   false when the figure is a target the run does not hold
--              itself to (default true)
--   ref_text   the reference as text when it is not a single number
--   note       free text shown beside the figure
--   detail     true for a data point (e.g. of a convergence plot) that the
--              report lists under its case rather than in the summary table
-- status is "pass" when every given tolerance or bound holds, otherwise
-- "fail" when asserted and "not reached" when not; "reported" when neither a
-- tolerance nor a bound is given. scripts/validation/report.py reads these
-- lines to build doc/validation.md; the test decks' assertions
-- (tests/decks/testlib.lua, T.expect) go through record{} too, so the test
-- suite and the report share one set of figures.
local mpm = rawget(_G, "mpm") or require "moraine"

local M = {}

local function encode_string(s)
  return '"' .. s:gsub('[%c"\\]', function(c)
    local named = { ['"'] = '\\"', ["\\"] = "\\\\", ["\n"] = "\\n", ["\t"] = "\\t", ["\r"] = "\\r" }
    return named[c] or string.format("\\u%04x", c:byte())
  end) .. '"'
end

local function encode_value(v)
  local t = type(v)
  if t == "number" then
    if v ~= v or v == math.huge or v == -math.huge then return "null" end -- JSON has no NaN/inf
    if math.type(v) == "integer" then return tostring(v) end
    return string.format("%.10g", v)
  elseif t == "boolean" then
    return tostring(v)
  elseif t == "string" then
    return encode_string(v)
  elseif v == nil then
    return "null"
  end
  error("results: cannot encode a " .. t, 3)
end

-- one-line JSON object of a flat table (keys sorted, so the output is stable)
local function json(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  local parts = {}
  for _, k in ipairs(keys) do parts[#parts + 1] = encode_string(k) .. ":" .. encode_value(t[k]) end
  return "{" .. table.concat(parts, ",") .. "}"
end

--- relative error |value - reference| / |reference| (nil without a reference)
local function relative_error(value, reference)
  if reference == nil then return nil end
  return math.abs(value - reference) / math.max(math.abs(reference), 1e-300)
end

-- whether every given tolerance or bound holds; nil when none is given
local function holds(r)
  local checked, ok = false, true
  if r.reference ~= nil and (r.rtol or r.atol) then
    checked = true
    ok = ok and math.abs(r.value - r.reference) <= (r.rtol or 0) * math.abs(r.reference) + (r.atol or 0)
  end
  if r.max ~= nil then checked, ok = true, ok and r.value <= r.max end
  if r.min ~= nil then checked, ok = true, ok and r.value >= r.min end
  if not checked then return nil end
  return ok and r.value == r.value -- NaN never holds
end

function M.record(t)
  assert(type(t) == "table" and type(t.id) == "string", "results.record: id (text) is required")
  assert(type(t.value) == "number", "results.record{id = " .. t.id .. "}: value must be a number")
  local r = {}
  for k, v in pairs(t) do r[k] = v end
  if r.asserted == nil then r.asserted = true end
  r.error = relative_error(r.value, r.reference)
  local ok = holds(r)
  if ok == nil then
    r.status = "reported"
  elseif ok then
    r.status = "pass"
  else
    r.status = r.asserted and "fail" or "not reached"
  end
  print("RESULT " .. json(r))
  io.stdout:flush()
  return r
end

--- results.write_csv(path, header, rows): rows (lists of numbers or text)
-- under a header (a list of column names) as CSV, numbers with 10
-- significant digits, nil as an empty cell. A relative path is in the output
-- directory; missing directories are created. Returns the path.
function M.write_csv(path, header, rows)
  if path:sub(1, 1) ~= "/" then path = mpm.outdir .. "/" .. path end
  local f = io.open(path, "w")
  if not f then
    local dir = path:match("^(.*)/[^/]*$")
    if dir then os.execute("mkdir -p '" .. dir:gsub("'", "'\\''") .. "'") end
    f = assert(io.open(path, "w"))
  end
  f:write(table.concat(header, ","), "\n")
  for _, r in ipairs(rows) do
    local t = {}
    for i = 1, #header do
      local v = r[i]
      if type(v) == "number" then t[i] = string.format("%.10g", v)
      elseif v == nil then t[i] = ""
      else t[i] = tostring(v) end
    end
    f:write(table.concat(t, ","), "\n")
  end
  f:close()
  return path
end


return M
