# Material physics against closed forms and experiments (issue 4, items 2-5 and 7).
# Included from tests/CMakeLists.txt after decks.cmake: it uses moraine_deck_test.
# Each deck asserts against its stated tolerance and prints the figures it got;
# the deck headers say what the quick and the full runs give. Quick variants
# take 3-10 s of CPU each (release build); the `--set full=true` variants
# (finer grids, longer runs: 20-60 s each) are labelled `slow` and `long`, so
# `ctest -LE slow` skips them and the sanitizer pass (-LE long) leaves them out.
if(COMMAND moraine_deck_test)
  # strip footing (002 §5.2): footing pressure vs Prandtl (2 + pi) c, 5 %
  moraine_deck_test(strip_footing strip_footing.lua LABELS physics)
  # plane Poiseuille / Couette start-up (004 §3.1): profiles 2 % / 3 %, APIC order >= 1.7
  moraine_deck_test(poiseuille poiseuille.lua LABELS physics)
  moraine_deck_test(couette couette.lua LABELS physics)
  # dam break (002 §5.4) vs Martin & Moyce (1952)
  moraine_deck_test(dam_break dam_break.lua LABELS physics)
  # sand column collapse (002 §5.5): comes to rest, runout reported
  moraine_deck_test(sand_column sand_column.lua LABELS physics)
  # energy balance of a Mohr-Coulomb collapse (000 Eqs. 67-69): |W_MPM| < 2 % of the drop, W_pl monotone
  moraine_deck_test(collapse_energy collapse_energy.lua LABELS physics)

  foreach(case strip_footing poiseuille couette dam_break sand_column collapse_energy)
    moraine_deck_test(${case}_full ${case}.lua ARGS --set full=true LABELS "physics;slow;long")
  endforeach()
endif()

# mu(I) on a rough inclined plane: the Bagnold profile (Jop et al. 2006), 12 % on 8 cells, 6 % on 16
if(COMMAND moraine_deck_test)
  moraine_deck_test(inclined_plane inclined_plane.lua LABELS physics)
  moraine_deck_test(inclined_plane_full inclined_plane.lua ARGS --set full=true LABELS "physics;slow;long")
endif()

# a strip footing pushed through a wall of prescribed motion: Prandtl's (2 + pi) c within 5 %, the reaction
# against the integrated stress; the full run refines to h = B/21 and adds a rough footing and Mohr-Coulomb
if(COMMAND moraine_deck_test)
  moraine_deck_test(prandtl_footing prandtl_footing.lua LABELS physics)
  moraine_deck_test(prandtl_footing_full prandtl_footing.lua ARGS --set full=true LABELS "physics;slow;long")
endif()
