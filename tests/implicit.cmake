# The implicit energy-momentum consistent MPM (src/implicit, paper 001, doc/implicit.md).
# The tangent and energy-identity unit test (tests/unit/test_implicit.c) is registered with the other unit tests.
moraine_deck_test(implicit_cylinders implicit_cylinders.lua)
# 6 s: the elasto-plastic collision and separation; up to 8 s one step needs 10 Newton iterations (doc/implicit.md)
moraine_deck_test(implicit_cylinders_plastic implicit_cylinders.lua ARGS --set material=von_mises --set mappings=FLIP --set time=6)
moraine_deck_test(implicit_cantilever implicit_cantilever.lua LABELS long)
# the same cantilever with the explicit step (point forces, FLIP, USF, CFL 0.5), for the comparison in doc/implicit.md
moraine_deck_test(explicit_cantilever explicit_cantilever.lua LABELS long)
