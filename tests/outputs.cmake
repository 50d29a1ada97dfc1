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
if(NOT DEFINED MORAINE_TEST_OUT)
  set(MORAINE_TEST_OUT ${CMAKE_CURRENT_BINARY_DIR}/out)
endif()
if(NOT DEFINED MORAINE_PYTHON)
  set(MORAINE_PYTHON /usr/bin/python3) # Debian's python3 with python3-vtk9, h5py, numpy
endif()
set(MORAINE_OUTPUTS_DIR ${MORAINE_TEST_OUT}/outputs)
set(MORAINE_PLOT ${CMAKE_SOURCE_DIR}/scripts/moraine-plot)

# ---- grid files (.vti) -------------------------------------------------------
add_test(NAME python.vti_write COMMAND test_vti ${MORAINE_OUTPUTS_DIR}/vti)
set_tests_properties(python.vti_write PROPERTIES LABELS python FIXTURES_SETUP outputs_vti)
add_test(NAME python.vti
         COMMAND ${MORAINE_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_vti.py ${MORAINE_OUTPUTS_DIR}/vti)
set_tests_properties(python.vti PROPERTIES LABELS python FIXTURES_REQUIRED outputs_vti)

# ---- HDF5 time series ----------------------------------------------------------
set(series_dir ${MORAINE_OUTPUTS_DIR}/series_h5)
add_test(NAME python.series_h5_write COMMAND test_series_h5 ${series_dir})
set_tests_properties(python.series_h5_write PROPERTIES LABELS python FIXTURES_SETUP outputs_series)
add_test(NAME python.series_h5
         COMMAND ${MORAINE_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_series_h5.py
                 ${series_dir}/series.h5 ${series_dir}/series.csv ${series_dir}/killed.h5 ${series_dir}/killed.csv)
set_tests_properties(python.series_h5 PROPERTIES LABELS python FIXTURES_REQUIRED outputs_series)

# ---- plots -----------------------------------------------------------------------
# auto always runs (matplotlib if installed, else gnuplot); each drawing tool
# found now is also tried on its own
set(plot_backends auto)
execute_process(COMMAND ${MORAINE_PYTHON} -c "import matplotlib"
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
           COMMAND ${MORAINE_PYTHON} ${MORAINE_PLOT} ${plot_dir}/energies_${backend}.png ${series_dir}/series.csv
                   E_kinetic E_gravity E_total --title "Energies (${backend})" --ylabel "energy (J)"
                   --backend ${backend})
  # the HDF5 series: a value recorded now and then, against the step, units from the file
  add_test(NAME plot.h5_${backend}
           COMMAND ${MORAINE_PYTHON} ${MORAINE_PLOT} ${plot_dir}/runout_${backend}.png ${series_dir}/series.h5
                   runout com_y --x step --backend ${backend})
  set_tests_properties(plot.csv_${backend} plot.h5_${backend} PROPERTIES
                       LABELS plot FIXTURES_REQUIRED outputs_series FIXTURES_SETUP outputs_plots)
  list(APPEND plot_files ${plot_dir}/energies_${backend}.png ${plot_dir}/runout_${backend}.png)
endforeach()

# a column the file does not have: refused, with the columns it has listed
add_test(NAME plot.unknown_column
         COMMAND ${MORAINE_PYTHON} ${MORAINE_PLOT} ${plot_dir}/never.png ${series_dir}/series.csv no_such_column)
set_tests_properties(plot.unknown_column PROPERTIES LABELS plot FIXTURES_REQUIRED outputs_series
                     PASS_REGULAR_EXPRESSION "has no column no_such_column; it has: step, time, dt, E_kinetic")

add_test(NAME python.png COMMAND ${MORAINE_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_png.py ${plot_files})
set_tests_properties(python.png PROPERTIES LABELS "python;plot" FIXTURES_REQUIRED "outputs_series;outputs_plots")
