-- moraine.sweep (lua/moraine/sweep.lua): parameter studies.
--  1. sweep.combinations gives every combination, in a fixed order;
--  2. sweep.run calls a function for each: the free-fall drop of a block
--     after a fixed time departs from g t^2 / 2 by dt / t (the scheme's
--     discrete trajectory, see free_fall.lua), so halving dt halves it (1 %);
--  3. sweep.decks runs tests/decks/axial_bar.lua as separate processes over
--     two grids and gathers its RESULT lines: v_cm(0) and the period within
--     the deck's own tolerances of 0.063662 m/s and 10 s; a combination whose
--     run fails (an unknown shape function) is a row with ok = false and the
--     deck's error in its output, not an error here;
--  4. sweep.write_csv writes one line per row.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local sweep = require "moraine.sweep"

-- 1.
local c = sweep.combinations{ b = { 1, 2 }, a = { "x", "y", "z" }, fixed = 7 }
T.check(#c == 6, "expected 6 combinations, got %d", #c)
T.check(c[1].a == "x" and c[1].b == 1 and c[2].b == 2 and c[6].a == "z" and c[6].fixed == 7,
        "combinations out of order: %s ... %s", sweep.label(c[1]), sweep.label(c[6]))

-- 2.
local g, t_end = 9.81, 0.2
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local rows = sweep.run{ params = { dt = { 1e-3, 5e-4 } }, fn = function(p)
  local sim <close> = mpm.simulation{ dim = 2, grid = { size = { 1, 2 }, cell = 0.1 }, gravity = { 0, -g },
                                      dt = { fixed = p.dt }, boundary = { all = "free" }, thermo = 0,
                                      diagnostics = false }
  sim:add_particles(mpm.box{ min = { 0.4, 1.5 }, max = { 0.6, 1.7 } }, { material = mat })
  local y0 = sim:diagnostics().com_y
  sim:run{ time = t_end }
  local drop = y0 - sim:diagnostics().com_y
  return { departure = drop / (g * t_end ^ 2 / 2) - 1 }
end }
T.check(rows[1].ok and rows[2].ok, "sweep.run: %s", rows[1].error or rows[2].error or "")
for _, r in ipairs(rows) do
  T.close(r.values.departure, r.params.dt / t_end, 0.01, "free-fall departure at dt = " .. r.params.dt)
end

-- 3.
local runs = sweep.decks{ deck = mpm.deck_dir .. "/axial_bar.lua",
                          params = { cells = { 16, 32 }, shape = { "linear", "no_such_shape" } } }
T.check(#runs == 4, "sweep.decks returned %d rows", #runs)
for _, r in ipairs(runs) do
  local id = string.format("axial_bar.%s_%d", r.params.shape, r.params.cells)
  if r.params.shape == "linear" then
    T.check(r.ok, "%s: the run failed: %s", sweep.label(r.params), r.output)
    T.close(r.values[id .. ".v0"], 0.063662, 0.025, id .. " v_cm(0) gathered")
    T.close(r.values[id .. ".period"], 10, 0.02, id .. " period gathered")
    print(string.format("sweep: %s period %.4f s", sweep.label(r.params), r.values[id .. ".period"]))
  else
    T.check(not r.ok and r.output:find("no_such_shape", 1, true),
            "%s: expected a failed run naming the shape, got exit %s: %s", sweep.label(r.params), tostring(r.exit),
            r.output)
  end
end

-- 4.
local path = sweep.write_csv(runs, "sweep.csv")
local lines = {}
for line in io.lines(path) do lines[#lines + 1] = line end
T.check(#lines == 5 and lines[1]:find("^cells,shape,ok,"), "sweep.csv: %d lines, header %s", #lines, lines[1])
T.done("sweep")
