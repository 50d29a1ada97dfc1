# Checks of the sources' shape, included from tests/CMakeLists.txt. Each
# script lists what it still allows today (issue 24 removes those entries)
# and fails on an entry no longer needed, so that the lists only shrink.
#   check.layers           no include from a module into one above it
#                          (core -> shape -> grid -> particles -> transfer ->
#                          material -> solver -> implicit -> io -> lua), no
#                          module cycle (scripts/check_layers.py)
#   check.function_length  no function over 80 lines in src/ and lua/, the
#                          transfer kernels' reference form under 300 lines
#                          (scripts/check_function_length.py)
#   check.selftest         both fail on a tree broken on purpose, one rule at
#                          a time (scripts/check_selftest.py)
foreach(check layers function_length selftest)
  add_test(NAME check.${check}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/scripts/check_${check}.py ${CMAKE_SOURCE_DIR})
  set_tests_properties(check.${check} PROPERTIES LABELS check ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
endforeach()
