-- moraine.sweep: parameter studies. Runs a function or a deck for every
-- combination of parameter values and gathers the results in one table.
--
--   local sweep = require "moraine.sweep"
--   local rows = sweep.decks{ deck = "tests/decks/axial_bar.lua",
--                             params = { cells = { 16, 32 }, shape = { "linear", "quadratic_bspline" } } }
--   for _, row in ipairs(rows) do
--     print(row.params.cells, row.params.shape, row.ok, row.results[2] and row.results[2].value)
--   end
--   sweep.write_csv(rows, "sweep.csv")
--
-- A deck run by sweep.decks is a separate moraine process (the running
-- executable, mpm.executable) with `--set NAME=VALUE` for each parameter and
-- its own output directory; its figures are the "RESULT {json}" lines it
-- prints (require "moraine.results", results.record{...}).
local results = require "moraine.results"
local mpm = rawget(_G, "mpm") or require "moraine"

local M = {}

local function sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  return keys
end

--- sweep.combinations(params): every combination of the value lists in
-- `params` ({name = {v1, v2, ...}}; a single value counts as a list of one),
-- as a list of {name = value} tables. Names vary in alphabetical order, the
-- last name fastest, so the order does not depend on the table's hashing.
function M.combinations(params)
  assert(type(params) == "table", "sweep.combinations: params must be a table {name = {values}}")
  local names = sorted_keys(params)
  local out = { {} }
  for _, name in ipairs(names) do
    local values = params[name]
    if type(values) ~= "table" then values = { values } end
    assert(#values > 0, "sweep: parameter '" .. name .. "' has no value")
    local next_out = {}
    for _, partial in ipairs(out) do
      for _, v in ipairs(values) do
        local c = {}
        for k, x in pairs(partial) do c[k] = x end
        c[name] = v
        next_out[#next_out + 1] = c
      end
    end
    out = next_out
  end
  return out
end

--- a short label of a combination: "cells=16,shape=linear"
function M.label(combination)
  local parts = {}
  for _, k in ipairs(sorted_keys(combination)) do parts[#parts + 1] = k .. "=" .. tostring(combination[k]) end
  return table.concat(parts, ",")
end

--- sweep.run{ params = {...}, fn = function(p) return {name = number, ...} end }:
-- calls fn in this deck for every combination. Returns a list of rows
-- { params = p, ok = true, values = <fn's table> } or, when fn raised an
-- error, { params = p, ok = false, error = message, values = {} }.
function M.run(t)
  assert(type(t) == "table" and type(t.fn) == "function", "sweep.run: fn (a function of the parameters) is required")
  local rows = {}
  for _, p in ipairs(M.combinations(t.params or {})) do
    local ok, v = pcall(t.fn, p)
    rows[#rows + 1] = ok and { params = p, ok = true, values = v or {} }
                         or { params = p, ok = false, error = tostring(v), values = {} }
  end
  return rows
end

-- decode the flat JSON object of a RESULT line (strings, numbers, true, false, null)
local function decode(line)
  local obj, pos = {}, 2
  local function skip() pos = line:find("[^%s]", pos) or #line + 1 end
  local function str()
    local out, i = {}, pos + 1
    while true do
      local c = line:sub(i, i)
      if c == "" then error("unterminated string") end
      if c == '"' then pos = i + 1 return table.concat(out) end
      if c == "\\" then
        local e = line:sub(i + 1, i + 1)
        if e == "u" then
          out[#out + 1] = utf8.char(tonumber(line:sub(i + 2, i + 5), 16))
          i = i + 6
        else
          out[#out + 1] = ({ n = "\n", t = "\t", r = "\r", b = "\b", f = "\f" })[e] or e
          i = i + 2
        end
      else
        out[#out + 1] = c
        i = i + 1
      end
    end
  end
  skip()
  if line:sub(pos, pos) == "}" then return obj end
  while true do
    skip()
    local key = str()
    skip()
    assert(line:sub(pos, pos) == ":", "expected ':'")
    pos = pos + 1
    skip()
    local c = line:sub(pos, pos)
    local value
    if c == '"' then
      value = str()
    else
      local word = line:match("^[^,}%s]+", pos)
      pos = pos + #word
      if word == "true" then value = true
      elseif word == "false" then value = false
      elseif word == "null" then value = nil
      else value = assert(tonumber(word), "bad value " .. word) end
    end
    obj[key] = value
    skip()
    local sep = line:sub(pos, pos)
    pos = pos + 1
    if sep == "}" then return obj end
    assert(sep == ",", "expected ',' or '}'")
  end
end

--- the RESULT records in a text (a run's standard output), as a list
function M.parse_results(text)
  local list = {}
  for line in text:gmatch("[^\n]+") do
    local json = line:match("^RESULT (%b{})")
    if json then
      local ok, r = pcall(decode, json)
      if ok then list[#list + 1] = r end
    end
  end
  return list
end

local function quote(s)
  return "'" .. tostring(s):gsub("'", "'\\''") .. "'"
end

--- sweep.decks{ deck = path, params = {...}, set = {name = value}, outdir = dir,
--               moraine = executable, quiet = true, overwrite = mpm.overwrite }:
-- runs `moraine DECK -q -o OUTDIR/<label> --set name=value ...` for every
-- combination (plus the fixed `set` options). OUTDIR defaults to
-- mpm.outdir .. "/sweep". Returns a list of rows
-- { params = p, ok = exit status 0, exit = code, outdir = dir,
--   results = {RESULT records}, values = {id = value}, output = stdout }.
-- A failed run is a row with ok = false (its error is in `output`), not an
-- error of the calling deck.
function M.decks(t)
  assert(type(t) == "table" and type(t.deck) == "string", "sweep.decks: deck (a path) is required")
  local exe = t.moraine or mpm.executable or "moraine"
  local base = t.outdir or (mpm.outdir .. "/sweep")
  local rows = {}
  for _, p in ipairs(M.combinations(t.params or {})) do
    local label = M.label(p):gsub("[^%w%.,=_-]", "_")
    local dir = base .. "/" .. (label ~= "" and label or "run")
    local cmd = { quote(exe), quote(t.deck), t.quiet == false and "" or "-q", "-o", quote(dir) }
    local overwrite = t.overwrite
    if overwrite == nil then overwrite = mpm.overwrite end
    if overwrite then cmd[#cmd + 1] = "--overwrite" end
    local sets = {}
    for k, v in pairs(t.set or {}) do sets[k] = v end
    for k, v in pairs(p) do sets[k] = v end
    for _, k in ipairs(sorted_keys(sets)) do cmd[#cmd + 1] = "--set " .. quote(k .. "=" .. tostring(sets[k])) end
    local pipe = assert(io.popen(table.concat(cmd, " ") .. " 2>&1", "r"))
    local output = pipe:read("a")
    local _, _, code = pipe:close()
    local list = M.parse_results(output)
    local values = {}
    for _, r in ipairs(list) do values[r.id] = r.value end
    rows[#rows + 1] = { params = p, ok = code == 0, exit = code, outdir = dir, results = list, values = values,
                        output = output }
  end
  return rows
end

--- sweep.write_csv(rows, path): one line per row, a column per parameter and
-- per value name (sorted), plus `ok`; relative paths go to mpm.outdir.
-- Returns the path.
function M.write_csv(rows, path)
  local pnames, vnames, seen = {}, {}, {}
  for _, row in ipairs(rows) do
    for k in pairs(row.params) do if not seen["p" .. k] then seen["p" .. k] = true; pnames[#pnames + 1] = k end end
    for k in pairs(row.values) do if not seen["v" .. k] then seen["v" .. k] = true; vnames[#vnames + 1] = k end end
  end
  table.sort(pnames)
  table.sort(vnames)
  local header, lines = {}, {}
  for _, k in ipairs(pnames) do header[#header + 1] = k end
  header[#header + 1] = "ok"
  for _, k in ipairs(vnames) do header[#header + 1] = k end
  for _, row in ipairs(rows) do
    local cells = {} -- indexed by column: a missing value is a hole (an empty cell)
    for i, k in ipairs(pnames) do cells[i] = row.params[k] end
    cells[#pnames + 1] = row.ok and 1 or 0
    for i, k in ipairs(vnames) do cells[#pnames + 1 + i] = row.values[k] end
    lines[#lines + 1] = cells
  end
  return results.write_csv(path, header, lines)
end

return M
