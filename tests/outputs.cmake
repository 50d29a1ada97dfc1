# Output files read back by other tools, included from tests/CMakeLists.txt.
#
# The C unit tests test_vti, test_series_h5 and test_provenance run on their
# own as unit.* (every tests/unit/test_*.c is registered there). Given a
# directory, test_vti and test_series_h5 also leave files in it; each such run
# is a fixture that the checks below require, so a check never reads stale
# files from an earlier run (a failed writer marks its checks "not run").
#
#   python.vti                .vti grid files and their .pvd read by VTK's
#                             vtkXMLImageDataReader (python3-vtk9)
#   python.series_h5          HDF5 series read by h5py and h5dump equal the
#                             CSV written beside them, including a series
#                             whose writer was killed with SIGKILL
#   plot.*                    scripts/moraine-plot draws those series, from
#                             CSV and from HDF5, with each drawing tool found
#   python.png                every PNG drawn is a valid, non-empty image
#   python.outputs_roundtrip  every .vtp/.vti/.pvd of a 2D and a 3D run equals the
#                             checkpoint of the same state; Lua reductions = numpy
#   python.vtk_forms          a collapse snapshot in every form of output{} (zlib,
#                             Float32, VTKHDF) equals the raw .vtp, TimeValue =
#                             the collection's time, zlib + Float32 >= 3x smaller;
#                             the deck's HDF5 series in xarray with 2D units
#   robust.sigkill            files left by runs killed with SIGKILL are whole
#   python.example_pngs       the examples' own PNG plots are valid images
set(MORAINE_OUTPUTS_DIR ${MORAINE_TEST_OUT}/outputs)
set(MORAINE_PLOT ${CMAKE_SOURCE_DIR}/scripts/moraine-plot)

# ---- grid files (.vti) -------------------------------------------------------
add_test(NAME python.vti_write COMMAND test_vti ${MORAINE_OUTPUTS_DIR}/vti)
set_tests_properties(python.vti_write PROPERTIES LABELS python FIXTURES_SETUP outputs_vti)
add_test(NAME python.vti
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_vti.py ${MORAINE_OUTPUTS_DIR}/vti)
set_tests_properties(python.vti PROPERTIES LABELS python FIXTURES_REQUIRED outputs_vti)

# ---- HDF5 time series ----------------------------------------------------------
set(series_dir ${MORAINE_OUTPUTS_DIR}/series_h5)
add_test(NAME python.series_h5_write COMMAND test_series_h5 ${series_dir})
set_tests_properties(python.series_h5_write PROPERTIES LABELS python FIXTURES_SETUP outputs_series)
add_test(NAME python.series_h5
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_series_h5.py
                 ${series_dir}/series.h5 ${series_dir}/series.csv ${series_dir}/killed.h5 ${series_dir}/killed.csv)
set_tests_properties(python.series_h5 PROPERTIES LABELS python FIXTURES_REQUIRED outputs_series)

# ---- plots -----------------------------------------------------------------------
# auto always runs (matplotlib if installed, else gnuplot); each drawing tool
# found now is also tried on its own
set(plot_backends auto)
execute_process(COMMAND ${Python3_EXECUTABLE} -c "import matplotlib"
                RESULT_VARIABLE no_matplotlib OUTPUT_QUIET ERROR_QUIET)
if(no_matplotlib EQUAL 0)
  list(APPEND plot_backends matplotlib)
endif()
find_program(MORAINE_GNUPLOT gnuplot)
if(MORAINE_GNUPLOT)
  list(APPEND plot_backends gnuplot)
endif()

set(plot_dir ${MORAINE_OUTPUTS_DIR}/plots)
set(plot_files "")
foreach(backend ${plot_backends})
  # the diagnostics CSV: energies against time
  add_test(NAME plot.csv_${backend}
           COMMAND ${Python3_EXECUTABLE} ${MORAINE_PLOT} ${plot_dir}/energies_${backend}.png ${series_dir}/series.csv
                   E_kinetic E_gravity E_total --title "Energies (${backend})" --ylabel "energy (J)"
                   --backend ${backend})
  # the HDF5 series: a value recorded now and then, against the step, units from the file
  add_test(NAME plot.h5_${backend}
           COMMAND ${Python3_EXECUTABLE} ${MORAINE_PLOT} ${plot_dir}/runout_${backend}.png ${series_dir}/series.h5
                   runout com_y --x step --backend ${backend})
  set_tests_properties(plot.csv_${backend} plot.h5_${backend} PROPERTIES
                       LABELS plot FIXTURES_REQUIRED outputs_series FIXTURES_SETUP outputs_plots)
  list(APPEND plot_files ${plot_dir}/energies_${backend}.png ${plot_dir}/runout_${backend}.png)
endforeach()

# a column the file does not have: refused, with the columns it has listed
add_test(NAME plot.unknown_column
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PLOT} ${plot_dir}/never.png ${series_dir}/series.csv no_such_column)
set_tests_properties(plot.unknown_column PROPERTIES LABELS plot FIXTURES_REQUIRED outputs_series
                     PASS_REGULAR_EXPRESSION "has no column no_such_column; it has: step, time, dt, E_kinetic")

add_test(NAME python.png COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_png.py ${plot_files})
set_tests_properties(python.png PROPERTIES LABELS "python;plot" FIXTURES_REQUIRED "outputs_series;outputs_plots")

# ---- every output against the checkpoint of the same state (must-show 1 and 4) --
# a 2D and a 3D run: each .vtp, .vti and .pvd read by VTK's readers equals the
# checkpoint saved at that snapshot (h5py), .pvd times equal the model times,
# and sim:reduce over all particles, a material, a region and a predicate
# equals numpy over the last .vtp
moraine_deck_test(outputs_roundtrip outputs_roundtrip.lua)
set_tests_properties(deck.outputs_roundtrip PROPERTIES FIXTURES_SETUP outputs_roundtrip)
add_test(NAME python.outputs_roundtrip
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_outputs_roundtrip.py
                 ${MORAINE_TEST_OUT}/outputs_roundtrip run2d run3d)
set_tests_properties(python.outputs_roundtrip PROPERTIES LABELS python FIXTURES_REQUIRED outputs_roundtrip)

# registered per-particle fields (set, read, reduced, written, checkpointed)
# and grid probes (tests/decks/particle_fields.lua); the storage itself is
# unit.test_user_fields
moraine_deck_test(particle_fields particle_fields.lua)

# ---- the forms of a snapshot and the series' record (tests/decks/vtk_forms.lua) --
moraine_deck_test(vtk_forms vtk_forms.lua)
set_tests_properties(deck.vtk_forms PROPERTIES FIXTURES_SETUP vtk_forms)
add_test(NAME python.vtk_forms
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_vtk_forms.py
                 ${MORAINE_TEST_OUT}/vtk_forms ${MORAINE_DECK_DIR}/vtk_forms.lua)
set_tests_properties(python.vtk_forms PROPERTIES LABELS python FIXTURES_REQUIRED vtk_forms)

# ---- SIGKILL in the middle of writing (must-show 5) ----------------------------
# 14 kills at random moments of a run writing 11 MB .vtp files, .vti, .pvd, an
# HDF5 series, a CSV and a checkpoint every step (about 15 s); every file left
# is read back whole. "long": the sanitizer pass leaves it to the release pass.
add_test(NAME robust.sigkill COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/robust/sigkill.sh $<TARGET_FILE:moraine>
                                     ${MORAINE_TEST_OUT}/robust_sigkill 14 ${Python3_EXECUTABLE})
set_tests_properties(robust.sigkill PROPERTIES LABELS "robust;long" ENVIRONMENT OMP_WAIT_POLICY=PASSIVE TIMEOUT 120)

# ---- the examples' own plots (must-show 6) --------------------------------------
# the column collapse (its gnuplot script) and the bouncing cube (moraine.plot,
# lua/moraine/plot.lua) in their quick form with plot=true; every PNG they
# announce must be a valid, non-empty image
set(example_plot_dir ${MORAINE_OUTPUTS_DIR}/example_plots)
add_test(NAME plot.example_column_collapse
         COMMAND moraine ${CMAKE_SOURCE_DIR}/examples/column_collapse/deck.lua -q -o ${example_plot_dir}/column_collapse --overwrite
                 --set quick=true --set plot=true)
add_test(NAME plot.example_bouncing_cube
         COMMAND moraine ${CMAKE_SOURCE_DIR}/examples/bouncing_cube/deck.lua -q -o ${example_plot_dir}/bouncing_cube --overwrite
                 --set quick=true --set plot=true)
set_tests_properties(plot.example_column_collapse plot.example_bouncing_cube PROPERTIES
                     LABELS "plot;example" FIXTURES_SETUP example_plots ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
set(collapse_pngs runout kinetic w_mpm lube AR1_FLIP_energies)
list(TRANSFORM collapse_pngs PREPEND ${example_plot_dir}/column_collapse/)
list(TRANSFORM collapse_pngs APPEND .png)
add_test(NAME python.example_pngs
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_png.py ${collapse_pngs}
                 ${example_plot_dir}/bouncing_cube/energies.png ${example_plot_dir}/bouncing_cube/momentum.png)
set_tests_properties(python.example_pngs PROPERTIES LABELS "python;plot" FIXTURES_REQUIRED example_plots)
# the collapse's front read back from the same run's VTK series (examples/column_collapse/front.py)
add_test(NAME python.collapse_front
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/examples/column_collapse/front.py
                 ${example_plot_dir}/column_collapse/AR1_FLIP_collapse.pvd)
set_tests_properties(python.collapse_front PROPERTIES LABELS "python;plot" FIXTURES_REQUIRED example_plots)

# ---- the run log, the summary, the thermo columns and the progress bar -------
# python.run_log: log.txt holds everything printed for runs that end well, fail,
# are interrupted or stopped by the watchdog; the summary's fields; thermo
# columns by name against diagnostics.csv; the bar on a pseudo-terminal
add_test(NAME python.run_log
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_run_log.py $<TARGET_FILE:moraine>
                 ${MORAINE_OUTPUTS_DIR}/run_log)
set_tests_properties(python.run_log PROPERTIES LABELS python ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)

# ---- velocity_gradient and vorticity (tests/decks/velocity_gradient.lua) --------
# rigid rotations (2D, 3D) and a simple shear: L and curl v exact, in every VTK form
moraine_deck_test(velocity_gradient velocity_gradient.lua)
set_tests_properties(deck.velocity_gradient PROPERTIES FIXTURES_SETUP velocity_gradient)
add_test(NAME python.velocity_gradient
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_velocity_gradient.py
                 ${MORAINE_TEST_OUT}/velocity_gradient)
set_tests_properties(python.velocity_gradient PROPERTIES LABELS python FIXTURES_REQUIRED velocity_gradient)
