# The implicit energy-momentum consistent MPM (src/implicit, paper 001, doc/implicit.md).
# The tangent and energy-identity unit test (tests/unit/test_implicit.c) is registered with the other unit tests.
moraine_deck_test(implicit_cylinders implicit_cylinders.lua)
# sim:run driving the implicit integrator: ends on time, equals the imp:step() loop bit for bit, W_MPM, outputs
moraine_deck_test(implicit_run implicit_run.lua)
# the elasto-plastic collision (001 §7.3) to 8 s; with min_node_mass = 0 one step after 6 s needs 10 Newton
# iterations, with the default 1e-3 at most 5 (doc/implicit.md)
moraine_deck_test(implicit_cylinders_plastic implicit_cylinders.lua
                  ARGS --set material=von_mises --set mappings=FLIP --set time=8 --set min_node_mass=1e-3)
# the ghost penalty (src/implicit/ghost.c): momenta to round-off, energy balance with the penalty's work counted
moraine_deck_test(implicit_cylinders_ghost implicit_cylinders.lua ARGS --set mappings=FLIP --set ghost=0.01)
# face conditions (slip walls) and a plate of prescribed velocity: uniaxial-strain Hencky stress, the plate's work booked
moraine_deck_test(implicit_boundary implicit_boundary.lua)
# the volumetric averaging (src/implicit/bbar.c), elastic FLIP and PIC and elasto-plastic FLIP: energy (with the
# dissipation) and linear momentum as without it, angular momentum to 1e-4; its tangent against differences is the
# unit test tests/unit/test_implicit_bbar.c
moraine_deck_test(implicit_cylinders_bbar implicit_cylinders.lua ARGS --set bbar=true --set min_node_mass=1e-3)
moraine_deck_test(implicit_cylinders_bbar_plastic implicit_cylinders.lua
                  ARGS --set material=von_mises --set mappings=FLIP --set bbar=true --set min_node_mass=1e-3)
moraine_deck_test(implicit_cantilever implicit_cantilever.lua LABELS long)
# the same cantilever with the explicit step (point forces, FLIP, USF, CFL 0.5), for the comparison in doc/implicit.md
moraine_deck_test(explicit_cantilever explicit_cantilever.lua LABELS long)
# the Taylor bar (001 §7.4) with ghost stabilisation and volumetric averaging, its first 10 us (27 steps, about a
# minute): every step's Newton converged, energy balance with the penalty counted; the full 80 us (compared with the
# finite-element length and radius) is the validation case implicit_taylor
moraine_deck_test(implicit_taylor implicit_taylor.lua ARGS --set time=10e-6 --set verbose=false LABELS long)
# cutbacks: a step not converged in max_iter iterations is retried at half dt (the elasto-plastic cylinders with
# max_iter = 3): without cutbacks the run stops with the error, with them every accepted step converges within the
# limit, dt halves per cut, energy + dissipation and momentum as without cuts
moraine_deck_test(implicit_cutbacks implicit_cutbacks.lua)
# restart: a checkpoint of an elasto-plastic implicit run holds the points' history (b_e, tau, psi, xi in the
# implicit_* particle fields); loaded with a new integrator it continues bit for bit as the straight run
moraine_deck_test(implicit_restart implicit_restart.lua)
