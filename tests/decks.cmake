# Deck tests: each runs `moraine DECK -q -o OUT` and passes when the deck's own
# assertions (tests/decks/testlib.lua) hold; a failed check exits non-zero with
# the deck's file and line.
set(MORAINE_DECK_DIR ${CMAKE_CURRENT_SOURCE_DIR}/decks)

# --overwrite: the directory holds the outputs of this test's previous run
function(moraine_deck_test name deck)
  cmake_parse_arguments(ARG "" "" "ARGS;LABELS" ${ARGN})
  add_test(NAME deck.${name}
           COMMAND moraine ${MORAINE_DECK_DIR}/${deck} -q -o ${MORAINE_TEST_OUT}/${name} --overwrite ${ARG_ARGS})
  # parallel ctest jobs share two cores: threads must not spin while waiting
  set_tests_properties(deck.${name} PROPERTIES LABELS "deck;${ARG_LABELS}" ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
endfunction()

moraine_deck_test(free_fall free_fall.lua)
# particles leaving through a free face with on_leave = "delete": mass and energy booked as outflow
moraine_deck_test(outflow outflow.lua)
# inflow sources: mass rho A v t (2D, 3D, a velocity function), a steady channel with outflow, the energy
# columns, a checkpoint bit for bit, sorting, particles added from a hook
moraine_deck_test(inflow inflow.lua)
# mass scaling: the stable dt grows by sqrt(factor), a slow compression ends in the same stress in fewer steps
moraine_deck_test(mass_scaling mass_scaling.lua)
# particle splitting: a bar pulled to 3x stays continuous (standard MPM leaves empty cells), a checkpoint bit for bit
moraine_deck_test(split_tension_bar split_tension_bar.lua)
# CPDI: the tension bar pulled to 3x stays whole with PIC, FLIP and APIC (standard MPM fractures); the bouncing
# cube's energy with CPDI (through the impact here, the whole 1.9 s under `long`)
moraine_deck_test(cpdi_tension_bar cpdi.lua ARGS --set part=bar)
moraine_deck_test(cpdi_bouncing_cube_short cpdi.lua ARGS --set part=cube --set time=0.6)
moraine_deck_test(cpdi_bouncing_cube cpdi.lua ARGS --set part=cube LABELS long)
# CPDI2: the same bar with tracked corners; a cellular flow in which CPDI's parallelograms part at the shared
# corners and CPDI2's quadrilaterals stay together
moraine_deck_test(cpdi2_tension_bar cpdi2.lua ARGS --set part=bar)
moraine_deck_test(cpdi2_vortex cpdi2.lua ARGS --set part=vortex)
# cpGIMP: the same bar stays whole with APIC and PIC (uGIMP fractures); FLIP reported
moraine_deck_test(cpgimp_tension_bar cpgimp.lua)
# point forces (sim:point_force, load_factor, clear_forces): momentum, energy, traction, checkpoint
moraine_deck_test(point_force point_force.lua)
# every setter (found in the method table) refuses NaN, inf and out-of-range values as its constructor key does
moraine_deck_test(setters setters.lua)
# many regions combined in one call nest as a balanced tree, under the limit of 1000 levels
moraine_deck_test(region_nesting region_nesting.lua)
moraine_deck_test(lithostatic lithostatic.lua)
# Coulomb friction faces against closed forms (slide, stick, stop, side wall)
# for every strategy of 000 Table 1, two shape functions each
moraine_deck_test(friction_2d friction.lua)
moraine_deck_test(friction_3d friction.lua ARGS --set dim=3 LABELS slow)
# rigid walls: an inclined plane (slide, stick, reaction at rest) and a pushing plate
moraine_deck_test(walls walls.lua)
moraine_deck_test(walls_restart walls_restart.lua)
moraine_deck_test(walls_3d walls_3d.lua LABELS slow)
moraine_deck_test(walls_rest_long walls.lua ARGS --set only=rest --set length=2.4 --set rest_cell=0.0125 --set average=0.6
                  --set strategies=FLIP,APIC LABELS slow)
# a disk rolling (gap_check) and sliding down an inclined plane: a against the closed forms; on the wall
# within 3 % at 16 cells per radius and 3 x 3 points per cell (APIC, FLIP)
moraine_deck_test(rolling_disk rolling_disk.lua ARGS --set only=slide,face,wall)
moraine_deck_test(rolling_disk_fine rolling_disk.lua ARGS --set only=fine LABELS slow)
# mesh walls from STL files: a cube mesh as the box wall, an incline, binary = ASCII, a checkpoint
moraine_deck_test(walls_mesh walls_mesh.lua)
# rigid bodies: free fall at g, fixed dofs, mass and inertia, momentum with the material, a restart bit for bit
moraine_deck_test(rigid_body rigid_body.lua)
# a rigid footing settling on a confined elastic layer: delta = (W/A) H / (lambda + 2 G), reaction = weight
moraine_deck_test(rigid_footing rigid_footing.lua)
# what feeds a sliding body's vibration: a long wave that friction makes grow
# under every strategy that keeps energy, and FLIP's short waves
moraine_deck_test(friction_layer friction_layer.lua)
# a layer of sand sliding to rest: mu g under every update that takes the holds of V (the friction bound
# counts the normal momentum the face stops there); FLIP's and APIC's running front reported
moraine_deck_test(sliding_layer sliding_layer.lua)
moraine_deck_test(axial_bar_linear axial_bar.lua ARGS --set shape=linear --set cells=16)
moraine_deck_test(axial_bar_quadratic axial_bar.lua ARGS --set shape=quadratic_bspline --set cells=32)
# scheme volumetric = "fbar": an elastic bar keeps its period (0.18 % and 1.34 %, against 0.12 % and 1.25 %
# without); the averaging keeps mass and momentum under every stress update, 2D and 3D, each kernel
moraine_deck_test(axial_bar_linear_fbar axial_bar.lua ARGS --set shape=linear --set cells=16 --set volumetric=fbar
                  --set stress_update=MUSL)
moraine_deck_test(axial_bar_quadratic_fbar axial_bar.lua ARGS --set shape=quadratic_bspline --set cells=32
                  --set volumetric=fbar)
moraine_deck_test(volumetric_fbar volumetric_fbar.lua)
# "long": physics runs of a minute or more; the sanitizer pass of
# scripts/test.sh --sanitize leaves them to the release pass (the code paths
# they use are all exercised under the sanitizers by the shorter tests)
moraine_deck_test(bouncing_cube_flip bouncing_cube.lua ARGS --set transfer=FLIP LABELS long)
moraine_deck_test(bouncing_cube_pic_family bouncing_cube_strategies.lua ARGS --set strategies=PIC,APIC,TPIC,AFLIP LABELS long)
moraine_deck_test(bouncing_cube_flip_family bouncing_cube_strategies.lua
                  ARGS --set strategies=PIC,FLIP,TFLIP,XPIC\(2\),XPIC\(3\),XPIC\(4\) LABELS long)
# USAVG against USF, USL strictly dissipative: FLIP at two time steps
moraine_deck_test(bouncing_cube_updates bouncing_cube_updates.lua ARGS --set strategies=FLIP LABELS long)
# the PIC family loses about half the energy at the impact under every stress update
moraine_deck_test(bouncing_cube_updates_pic bouncing_cube_updates.lua ARGS --set strategies=PIC,APIC,TPIC --set a_tau=0.05
                  LABELS long)
moraine_deck_test(rotating_disk rotating_disk.lua)
# 000 App. B.1: the bouncing disk of Love & Sulsky, PIC, FLIP, APIC under USL (the whole 100 s; a_tau = 0.05
# under `long`)
moraine_deck_test(bouncing_disk bouncing_disk.lua)
moraine_deck_test(bouncing_disk_dt bouncing_disk.lua ARGS --set a_tau=0.05 LABELS long)
# 000 App. B.2: the rotating disk of Jiang et al., PIC, FLIP, APIC on two meshes (0.25 s at two steps; the
# 4 s and a_tau = 0.2 to 0.01 under `long`)
moraine_deck_test(spinning_disk_apic spinning_disk_apic.lua ARGS --set time=0.25 --set a_tau=0.2,0.1)
moraine_deck_test(simple_shear simple_shear.lua)
moraine_deck_test(settling settling.lua)
moraine_deck_test(disks_cfl disks_cfl.lua)
moraine_deck_test(checkpoint_workflow checkpoint_workflow.lua)
# sort_every: the same physics by id, changed indices, kept by checkpoints
moraine_deck_test(sort_every sort_every.lua)
moraine_deck_test(rotating_cube rotating_cube.lua ARGS --set time=10)
# APIC's angular-momentum loss rate: halves with dt, about 24x at 5x the spin (000 Figs. 8, 9);
# 5 s here, 000's 400 s as the validation case
moraine_deck_test(rotating_cube_scaling rotating_cube_scaling.lua ARGS --set time=5 --set spin10=false)
moraine_deck_test(rotating_cube_scaling_full rotating_cube_scaling.lua LABELS long)
# PIC's W_MPM during the settling is a function of t * dt (000 Fig. 12b)
moraine_deck_test(pic_wmpm_collapse pic_wmpm_collapse.lua)
moraine_deck_test(pic_wmpm_collapse_full pic_wmpm_collapse.lua
                  ARGS --set dts=2.92e-6,1.46e-6,3.65e-7 --set samples=40 --set steps=1750 LABELS long)
# linear shapes: APIC, AFLIP and TFLIP keep the angular momentum (mass-weighted affine fit)
moraine_deck_test(rotating_cube_linear rotating_cube.lua ARGS --set time=10 --set shape=linear
                  --set transfer=APIC)
# linear shapes, affine and Taylor transfers: a block sliding on a friction floor at several time steps
moraine_deck_test(apic_linear_slide apic_linear_slide.lua)
# the parameter-sweep helper lua/moraine/sweep.lua (runs axial_bar.lua four times)
moraine_deck_test(sweep sweep.lua LABELS lua)
# moraine.presets and moraine.geometry
moraine_deck_test(presets_geometry presets_geometry.lua LABELS lua)
# a material written in Lua against linear_elastic (deck and driver), its history through a checkpoint
moraine_deck_test(lua_material lua_material.lua)
# mu_i and cam_clay: their history variables through a checkpoint, bit for bit
moraine_deck_test(granular_restart granular_restart.lua)
# a vertical cut stands below the limit-analysis lower bound and collapses above the upper bound
moraine_deck_test(vertical_cut vertical_cut.lua)

# VTK files read back by the real VTK reader
moraine_deck_test(vtk_output vtk_output.lua)
add_test(NAME python.vtk_run_readback
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_run_vtk.py
                 ${MORAINE_TEST_OUT}/vtk_output run2d series3d/run3d)
set_tests_properties(python.vtk_run_readback PROPERTIES DEPENDS deck.vtk_output LABELS python)
add_test(NAME python.vtk_roundtrip_write COMMAND test_vtk ${MORAINE_TEST_OUT}/vtk_roundtrip)
add_test(NAME python.vtk_roundtrip
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_vtk_roundtrip.py
                 ${MORAINE_TEST_OUT}/vtk_roundtrip)
set_tests_properties(python.vtk_roundtrip PROPERTIES DEPENDS python.vtk_roundtrip_write LABELS python)

# Bad input: every deck in tests/bad/ must fail with the message on its first line
file(GLOB MORAINE_BAD_DECKS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/bad/*.lua)
foreach(deck ${MORAINE_BAD_DECKS})
  get_filename_component(name ${deck} NAME_WE)
  add_test(NAME bad.${name}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/bad/run.sh $<TARGET_FILE:moraine> ${deck} ${MORAINE_TEST_OUT}/bad/${name})
  set_tests_properties(bad.${name} PROPERTIES LABELS bad)
endforeach()

# The examples run (shortened through --set) so they cannot rot
file(GLOB MORAINE_EXAMPLES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/examples/*/deck.lua)
foreach(deck ${MORAINE_EXAMPLES})
  get_filename_component(dir ${deck} DIRECTORY)
  get_filename_component(name ${dir} NAME)
  add_test(NAME example.${name}
           COMMAND moraine ${deck} -q -o ${MORAINE_TEST_OUT}/example_${name} --overwrite --set quick=true)
  set_tests_properties(example.${name} PROPERTIES LABELS example)
endforeach()
# the footing example's diagnostics read back: the E_bodies, W_bodies columns and W_MPM
set_tests_properties(example.rigid_footing PROPERTIES FIXTURES_SETUP rigid_footing)
add_test(NAME python.body_series
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_body_series.py
                 ${MORAINE_TEST_OUT}/example_rigid_footing)
set_tests_properties(python.body_series PROPERTIES LABELS python FIXTURES_REQUIRED rigid_footing)
# the inflow example's diagnostics read back: the E_inflow, W_inflow, E_outflow columns and W_MPM
set_tests_properties(example.channel_inflow PROPERTIES FIXTURES_SETUP channel_inflow)
add_test(NAME python.inflow_series
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_inflow_series.py
                 ${MORAINE_TEST_OUT}/example_channel_inflow)
set_tests_properties(python.inflow_series PROPERTIES LABELS python FIXTURES_REQUIRED channel_inflow)
# the extrusion example's picture drawn from its snapshots through VTK's reader
set_tests_properties(example.extrusion PROPERTIES FIXTURES_SETUP extrusion)
add_test(NAME python.extrusion_plot
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/examples/extrusion/plot.py
                 ${MORAINE_TEST_OUT}/example_extrusion ${MORAINE_TEST_OUT}/example_extrusion/velocity.png)
set_tests_properties(python.extrusion_plot PROPERTIES LABELS python FIXTURES_REQUIRED extrusion)

# Robustness: a signal stops a run cleanly with a checkpoint that continues
# bit for bit; a failed run leaves a checkpoint h5py reads
add_test(NAME robust.sigint COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/robust/sigint.sh $<TARGET_FILE:moraine>
                                    ${MORAINE_TEST_OUT}/robust_sigint)
set_tests_properties(robust.sigint PROPERTIES LABELS robust ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
add_test(NAME robust.failed_state
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/robust/check_failed_state.py
                 ${MORAINE_TEST_OUT}/bad/unstable/simulation_failed.h5)
set_tests_properties(robust.failed_state PROPERTIES DEPENDS bad.unstable LABELS robust)

# The installed tree finds lua/moraine/ next to its executable
add_test(NAME install.lua_library COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/install_check.sh ${CMAKE_BINARY_DIR}
                                          ${CMAKE_CURRENT_BINARY_DIR}/install_prefix)
set_tests_properties(install.lua_library PROPERTIES LABELS install)
# The installed C API (pkg-config, find_package) runs the drop example bit for
# bit as the deck does, and a stock lua5.4 loads the C module. Not in a
# sanitised build: a program that is not (lua5.4, a plain cc build) cannot
# load a sanitised library, whose runtime must come first; the release pass
# runs it.
if(NOT MORAINE_SANITIZE AND NOT MORAINE_FUZZ)
  add_test(NAME install.c_api COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/install_c_api.sh ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}
                                      ${CMAKE_CURRENT_BINARY_DIR}/install_c_api ${Python3_EXECUTABLE})
  set_tests_properties(install.c_api PROPERTIES LABELS install)
endif()

# HDF5 series and grid snapshots of a real run
moraine_deck_test(series_output series_output.lua)
add_test(NAME python.series_run
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_series_h5.py
                 ${MORAINE_TEST_OUT}/series_output/diagnostics.h5 ${MORAINE_TEST_OUT}/series_output/diagnostics.csv
                 --extra-columns)
set_tests_properties(python.series_run PROPERTIES DEPENDS deck.series_output LABELS python)
add_test(NAME python.vti_run
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_grid_run.py ${MORAINE_TEST_OUT}/series_output s 10 10)
set_tests_properties(python.vti_run PROPERTIES DEPENDS deck.series_output LABELS python)

# contact between bodies (solver/contact.h): two elastic disks (and two balls in 3D) collide and
# separate (momentum to round-off, no overlap beyond a cell, energy kept), a block slides on another
# by Coulomb's law
# (contact_disks_single: the single field, and bodies without a pair are labels, bit for bit).
# FLIP keeps the energy as the single field does, both with a first-order error of the step:
# contact's is 1.117 (USF) and 1.095 (MUSL) times the single field's in 2D, asserted within 1.15
# times, and 0.98 times it in 3D
moraine_deck_test(contact_disks contact_disks.lua ARGS --set compare=true --set compare_factor=1.15 LABELS physics)
moraine_deck_test(contact_disks_apic contact_disks.lua ARGS --set transfer=APIC --set energy_min=0.5 --set compare=true LABELS physics)
moraine_deck_test(contact_disks_musl contact_disks.lua ARGS --set stress_update=MUSL --set compare=true --set compare_factor=1.15 LABELS physics)
moraine_deck_test(contact_disks_3d contact_disks.lua ARGS --set dim=3 --set compare=true LABELS physics)
# the same state on 1 and 2 threads (the bodies are scattered side by side, each in particle order):
# 6,400 particles, enough for the loops to take both threads; the checkpoints compared object by object
foreach(threads 1 2)
  moraine_deck_test(contact_disks_threads${threads} contact_disks.lua
                    ARGS --threads ${threads} --set cell=0.0125 --set save=true LABELS physics)
  set_tests_properties(deck.contact_disks_threads${threads} PROPERTIES FIXTURES_SETUP contact_threads)
endforeach()
add_test(NAME python.contact_threads
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/scripts/bitwise/compare.py
                 ${MORAINE_TEST_OUT}/contact_disks_threads1 ${MORAINE_TEST_OUT}/contact_disks_threads2)
set_tests_properties(python.contact_threads PROPERTIES LABELS python FIXTURES_REQUIRED contact_threads)
moraine_deck_test(contact_slide contact_slide.lua ARGS --set transfer=APIC LABELS physics)
moraine_deck_test(contact_slide_flip contact_slide.lua LABELS physics)
moraine_deck_test(contact_slide_flip_mu02 contact_slide.lua ARGS --set mu=0.2 LABELS physics)
moraine_deck_test(contact_slide_frictionless contact_slide.lua ARGS --set mu=0 LABELS physics)
moraine_deck_test(contact_slide_pic contact_slide.lua ARGS --set transfer=PIC LABELS physics)
moraine_deck_test(contact_slide_stick contact_slide.lua ARGS --set transfer=APIC --set mu=0.7 LABELS physics)
moraine_deck_test(contact_stack_at_rest contact_slide.lua ARGS --set transfer=APIC --set theta=0 LABELS physics)
moraine_deck_test(contact_stack_at_rest_flip contact_slide.lua ARGS --set theta=0 --set cell=0.025 LABELS physics)
moraine_deck_test(contact_disks_single contact_disks.lua ARGS --set contact=false LABELS physics)
