# Granular column settling and collapse (000 §5) through lua/moraine/collapse.lua,
# included from tests/CMakeLists.txt after decks.cmake (it uses moraine_deck_test).
# The quick variant takes about 10 s of CPU; `--set full=true` adds a finer
# time step and TFLIP, label `slow`. collapse_s4 is 000's series S4 (AR 0.6,
# 2.4 and 3 with FLIP and AFLIP) at a coarser step, about 15 s; the series as
# 000 ran it is a validation case (scripts/validation/cases.toml).
if(COMMAND moraine_deck_test)
  moraine_deck_test(column_collapse column_collapse.lua LABELS collapse)
  moraine_deck_test(column_collapse_full column_collapse.lua ARGS --set full=true LABELS "collapse;slow")
  moraine_deck_test(collapse_s4 collapse_s4.lua ARGS --set quick=true LABELS collapse)
endif()

# the collapse with mu(I) and Modified Cam-Clay beside Mohr-Coulomb (AR = 2)
if(COMMAND moraine_deck_test)
  moraine_deck_test(granular_collapse granular_collapse.lua LABELS collapse)
  moraine_deck_test(granular_collapse_full granular_collapse.lua ARGS --set full=true LABELS "collapse;slow;long")
endif()

# 000's series S3 (N_mppc 1 to 49, AR 1) without and with particle splitting;
# the quick variant N_mppc 1 and 4 only (about 10 s of CPU)
if(COMMAND moraine_deck_test)
  moraine_deck_test(collapse_s3 collapse_s3.lua ARGS --set quick=true LABELS collapse)
  moraine_deck_test(collapse_s3_full collapse_s3.lua LABELS "collapse;slow;long")
endif()

# 000's series S2 (l_cell 10 to 5 cm, AR 1); the quick variant 10 and 5 cm
# only (about 20 s of CPU), the four cells in the validation report
if(COMMAND moraine_deck_test)
  moraine_deck_test(collapse_s2 collapse_s2.lua ARGS --set quick=true LABELS collapse)
endif()
