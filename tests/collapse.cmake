# Granular column settling and collapse (000 §5) through lua/moraine/collapse.lua,
# included from tests/CMakeLists.txt after decks.cmake (it uses moraine_deck_test).
# The quick variant takes about 10 s of CPU; `--set full=true` adds the other
# aspect ratios, a finer time step and TFLIP (about a minute), label `slow`.
if(COMMAND moraine_deck_test)
  moraine_deck_test(column_collapse column_collapse.lua LABELS collapse)
  moraine_deck_test(column_collapse_full column_collapse.lua ARGS --set full=true LABELS "collapse;slow")
endif()

# the collapse with mu(I) and Modified Cam-Clay beside Mohr-Coulomb (AR = 2)
if(COMMAND moraine_deck_test)
  moraine_deck_test(granular_collapse granular_collapse.lua LABELS collapse)
  moraine_deck_test(granular_collapse_full granular_collapse.lua ARGS --set full=true LABELS "collapse;slow;long")
endif()
