-- 000's series S3 (000 Table 5, §5.3): the granular column of aspect ratio 1
-- collapses with FLIP, l_cell = 10 cm, N_mppc = 1, 4, 9, 16, 25 and 49
-- (per_axis 1, 2, 3, 4, 5, 7), settled as 000 §5.1, Mohr-Coulomb of 000
-- Table 2, floor mu = 0.3, boundary-modified cubic B-splines, USF
-- (moraine.collapse) -- once as 000 ran it and once with particle splitting
-- (simulation{split}, doc/numerics.md "Particle splitting"), the remedy 000
-- §5.3 proposes after FEMLIP: "the size of the domains [...] would be
-- tracked, and a material point be split into two if its domain became too
-- large".
--
-- Reference: "the final L_x is 25% higher for N_mppc = 49 than for
-- N_mppc = 1" (000 §5.3). The spread is (L_x(49) - L_x(1)) / L_x(1), L_x the
-- column width of 000 Eq. 70 (from the furthest particle, in whole cells);
-- the same from the furthest particle's position itself is reported too.
-- The issue's target: splitting cuts the spread at least in half.
-- Both settled columns of a count are the same checkpoint: only the
-- collapse differs. Splitting: {stretch = 1.5, max_level = 4} (--set
-- stretch=... --set max_level=...): a particle splits once its domain is
-- 1.5 times as long as at seeding, at most 16 particles from one.
--
-- a_tau = 0.2 (dt = 2.3e-4 s) rather than 000's 1.25e-3: 000 §5.2 finds
-- FLIP's runout independent of dt, and so does moraine (doc/validation.md,
-- column_collapse_lube); --set a_tau=1.25e-3 runs 000's step.
--
-- Asserted: splitting narrows the spread, in magnitude (a wider spread
-- with splitting fails); with splitting every column comes to rest and W_MPM stays below
-- 1 % of |Delta E_p^stable| (000, Eq. 69; a split conserves E_k + E_g + E_el,
-- so it must not show in the balance); splitting made particles.
-- Reported: both spreads, and their ratio against the target 0.5.
--
-- --set quick=true (the quick suite): N_mppc 1 and 4 only, the same
-- assertions on that spread.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local collapse = require "moraine.collapse"
local quick = mpm.param("quick", false)
local a_tau = mpm.param("a_tau", 0.2)
local counts = T.list(mpm.param("per_axis", quick and "1,2" or "1,2,3,4,5,7"))
local SPLIT = { stretch = mpm.param("stretch", 1.5), max_level = math.tointeger(mpm.param("max_level", 4)) }

-- --set cpdi=true adds a third run of the counts in cpdi_per_axis (1, 2, 3):
-- CPDI (`shape = "cpdi"`, doc/numerics.md) as the domain-tracking remedy
-- 000 §5.3 describes ("if one was to attribute an initial domain to each
-- material point"), settled and collapsed with it under the particle CFL
-- step dt = {cfl = cpdi_cfl} (0.2, about a_tau = 0.2), which shortens with
-- the domains' gradients: the flowing sand comes apart, F records the
-- separation as stretch, and the thin domains of the shear band spread over
-- several cells, where a fixed a_tau step loses stability (doc/numerics.md,
-- "CPDI in a granular flow"). Its spread, |W_MPM| and the counts whose run
-- the engine stopped are reported, not asserted.
local with_cpdi = mpm.param("cpdi", false)
local cpdi_cfl = mpm.param("cpdi_cfl", 0.2)
local cpdi_counts = {}
for _, text in ipairs(T.list(mpm.param("cpdi_per_axis", "1,2,3"))) do cpdi_counts[tonumber(text)] = true end
local cpdi_stopped = {}

local rows = {}
local csv = assert(io.open(mpm.outdir .. "/collapse_s3.csv", "w"))
csv:write("N_mppc,L_x,L_x_split,L_x_cpdi,max_x,max_x_split,max_x_cpdi\n")
for _, text in ipairs(counts) do
  local n = math.tointeger(tonumber(text)) or error("per_axis: '" .. text .. "' is not a whole number")
  local base = collapse.run{ aspect_ratio = 1, strategy = "FLIP", a_tau = a_tau, per_axis = n, stop_at_rest = true,
                             name = "standard_N" .. n * n }
  local split = collapse.run{ aspect_ratio = 1, strategy = "FLIP", a_tau = a_tau, per_axis = n, stop_at_rest = true,
                              settled = base.files.settled, split = SPLIT, name = "split_N" .. n * n }
  local cpdi
  if with_cpdi and cpdi_counts[n] then -- a run the engine stops is reported, not fatal
    local ok, r = pcall(collapse.run, { aspect_ratio = 1, strategy = "FLIP", dt_policy = { cfl = cpdi_cfl }, per_axis = n,
                                        stop_at_rest = true, shape = "cpdi", shape_boundary = "extended",
                                        name = "cpdi_N" .. n * n })
    if ok then cpdi = r else cpdi_stopped[#cpdi_stopped + 1] = n * n; print("N_mppc " .. n * n .. " with CPDI: " .. tostring(r)) end
  end
  for _, r in ipairs{ base, split, cpdi } do print(collapse.summary(r) .. string.format("  N_mppc %d, %d particles", n * n, r.particles)) end
  T.check(split.t_rest ~= nil, "N_mppc %d with splitting: not at rest after %.2f s", n * n, split.time)
  T.check(split.particles > base.particles, "N_mppc %d: no particle was split", n * n)
  T.expect{ id = string.format("collapse_s3.W_MPM_split_N%d", n * n),
            what = string.format("N_mppc = %d with splitting: |W_MPM| / |dE_p^stable| (000, Eq. 69)", n * n),
            value = 100 * split.W_MPM_ratio, max = 1, unit = "%" }
  if cpdi then
    T.expect{ id = string.format("collapse_s3.W_MPM_cpdi_N%d", n * n),
              what = string.format("N_mppc = %d with CPDI: |W_MPM| / |dE_p^stable| (000, Eq. 69)", n * n),
              value = 100 * cpdi.W_MPM_ratio, max = 1, unit = "%", asserted = false }
  end
  csv:write(string.format("%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", n * n, base.L_x, split.L_x, cpdi and cpdi.L_x or -1,
                          base.max_x, split.max_x, cpdi and cpdi.max_x or -1))
  rows[#rows + 1] = { n = n * n, base = base, split = split, cpdi = cpdi }
end
csv:close()

local first, last = rows[1], rows[#rows]
local function spread(key, what) return (last[key][what] - first[key][what]) / first[key][what] end
local s0, s1 = spread("base", "L_x"), spread("split", "L_x")
print(string.format("\n%8s %12s %12s %12s %12s %12s", "N_mppc", "L_x (m)", "split", "CPDI", "max x (m)", "split"))
for _, r in ipairs(rows) do
  print(string.format("%8d %12.2f %12.2f %12s %12.3f %12.3f", r.n, r.base.L_x, r.split.L_x,
                      r.cpdi and string.format("%.2f", r.cpdi.L_x) or "-", r.base.max_x, r.split.max_x))
end
local range = string.format("N_mppc %d -> %d", first.n, last.n)
T.expect{ id = "collapse_s3.spread", what = range .. ": L_x spread without splitting (000 §5.3: +25 % from 1 to 49)",
          value = 100 * s0, reference = not quick and 25 or nil, unit = "%", asserted = false }
T.expect{ id = "collapse_s3.spread_split", what = range .. ": L_x spread with splitting", value = 100 * s1, unit = "%",
          asserted = false }
T.expect{ id = "collapse_s3.spread_max_x", what = range .. ": furthest-particle spread without splitting",
          value = 100 * spread("base", "max_x"), unit = "%", asserted = false }
T.expect{ id = "collapse_s3.spread_max_x_split", what = range .. ": furthest-particle spread with splitting",
          value = 100 * spread("split", "max_x"), unit = "%", asserted = false }
T.expect{ id = "collapse_s3.spread_ratio", what = range .. ": L_x spread with splitting / without (target: at most 0.5)",
          value = s1 / s0, reference = 0.5, asserted = false }
if with_cpdi then
  T.expect{ id = "collapse_s3.cpdi_stopped", what = "CPDI runs stopped by the engine (N_mppc " ..
            (#cpdi_stopped > 0 and table.concat(cpdi_stopped, ", ") or "none") .. ")",
            value = #cpdi_stopped, max = 0, asserted = false }
  local lo, hi
  for _, r in ipairs(rows) do
    if r.cpdi then lo, hi = lo or r, r end
  end
  if lo and hi ~= lo then
    T.expect{ id = "collapse_s3.spread_cpdi",
              what = string.format("N_mppc %d -> %d: L_x spread with CPDI (dt = {cfl = %g})", lo.n, hi.n, cpdi_cfl),
              value = 100 * (hi.cpdi.L_x - lo.cpdi.L_x) / lo.cpdi.L_x, unit = "%", asserted = false }
    T.expect{ id = "collapse_s3.spread_cpdi_base", what = string.format("N_mppc %d -> %d: the same without CPDI",
              lo.n, hi.n), value = 100 * (hi.base.L_x - lo.base.L_x) / lo.base.L_x, unit = "%", asserted = false }
  end
end
T.check(math.abs(s1) < math.abs(s0), "%s: splitting did not narrow the spread (%.1f %% with, %.1f %% without)", range,
        100 * s1, 100 * s0)
T.check(math.abs(spread("split", "max_x")) < math.abs(spread("base", "max_x")),
        "%s: splitting did not narrow the furthest-particle spread", range)
T.done("collapse_s3")
