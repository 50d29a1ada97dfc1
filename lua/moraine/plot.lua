-- moraine.plot: PNG line plots of a run's time series from a deck, through
-- scripts/moraine-plot (matplotlib, else gnuplot; see `moraine-plot --help`).
--
--   local plot = require "moraine.plot"
--   plot.series{ png = "energies.png", file = "diagnostics.csv",
--                columns = { "E_kinetic", "E_gravity", "E_elastic", "E_total" },
--                title = "Energies", ylabel = "energy (J)" }
--
-- Fields:
--   png       output file, relative to the output directory (-o)      (required)
--   file      CSV or HDF5 series, relative to the output directory    (required)
--   columns   list of column names to draw                             (required)
--   x         column along the x axis                                  (default "time")
--   title, xlabel, ylabel   text
--   logy      true: logarithmic y axis
--   backend   "auto" (default), "matplotlib" or "gnuplot"
-- Returns true, or false and a message (the deck decides whether a missing
-- drawing tool is an error). The script is found through the environment
-- variable MORAINE_PLOT, next to the moraine executable (an installed tree),
-- in the source tree's scripts/ (a build tree), then on PATH.
local M = {}

local function quote(s)
  return "'" .. tostring(s):gsub("'", "'\\''") .. "'"
end

local function exists(path)
  local f = io.open(path, "r")
  if f then f:close() end
  return f ~= nil
end

function M.script()
  local env = os.getenv("MORAINE_PLOT")
  if env and env ~= "" then return env end
  local bin = (mpm.executable or ""):match("^(.*)/[^/]*$")
  if bin and exists(bin .. "/moraine-plot") then return bin .. "/moraine-plot" end
  local me = package.searchpath("moraine.plot", package.path)
  local lib = me and me:match("^(.*)/moraine/plot%.lua$")
  if lib and exists(lib .. "/../scripts/moraine-plot") then return lib .. "/../scripts/moraine-plot" end
  return "moraine-plot"
end

local function in_outdir(path)
  if path:sub(1, 1) == "/" then return path end
  return mpm.outdir .. "/" .. path
end

function M.series(t)
  assert(type(t) == "table", "plot.series{}: expected a table")
  assert(type(t.png) == "string", "plot.series{}: png = file name is required")
  assert(type(t.file) == "string", "plot.series{}: file = CSV or HDF5 series is required")
  assert(type(t.columns) == "table" and #t.columns > 0, "plot.series{}: columns = { names } is required")
  local script = M.script()
  -- a path is run by Debian's python3 (its matplotlib); a bare name is looked up on PATH
  local cmd = { script:find("/") and "/usr/bin/python3 " .. quote(script) or quote(script),
                quote(in_outdir(t.png)), quote(in_outdir(t.file)) }
  for _, c in ipairs(t.columns) do cmd[#cmd + 1] = quote(c) end
  for _, key in ipairs{ "x", "title", "xlabel", "ylabel", "backend" } do
    if t[key] then cmd[#cmd + 1] = "--" .. key .. " " .. quote(t[key]) end
  end
  if t.logy then cmd[#cmd + 1] = "--logy" end
  local ok, _, code = os.execute(table.concat(cmd, " "))
  if ok then return true end
  return false, string.format("moraine-plot failed (exit status %s) drawing %s", tostring(code), t.png)
end

return M
