-- Stability of a vertical cut (examples/vertical_cut): limit analysis
-- brackets the critical stability number N = gamma H / c of a vertical cut in
-- a frictionless soil between 2.83 and 3.83 (Chen 1975). The cut must stand
-- below the lower bound (N = 2.5: crest settlement under 1 % of H after
-- 1.5 s) and collapse above the upper bound (N = 5: crest settlement above
-- 5 % of H, largest displacement above 10 % of H).
-- Cells of H / 10 (the example's default).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local function cut(N) return T.run_example("../../examples/vertical_cut/deck.lua", { N = N, quick = true }) end
local stands, falls = cut(2.5), cut(5)
T.expect{ id = "vertical_cut.stands", what = "crest settlement / H at N = 2.5 (below the lower bound 2.83)",
          value = stands.settlement / stands.H, max = 0.01 }
T.expect{ id = "vertical_cut.collapses", what = "crest settlement / H at N = 5 (above the upper bound 3.83)",
          value = falls.settlement / falls.H, min = 0.05 }
T.expect{ id = "vertical_cut.collapse_displacement", what = "largest displacement / H at N = 5",
          value = falls.largest_displacement / falls.H, min = 0.1 }
T.done("vertical_cut")
