# Robustness tests of tests/robust/ added for bad outputs, signals, unstable
# runs and warnings (doc/errors.md lists them with the message each shows).
set(MORAINE_ROBUST_DIR ${CMAKE_CURRENT_SOURCE_DIR}/robust)
add_test(NAME robust.disk_full
         COMMAND ${MORAINE_ROBUST_DIR}/disk_full.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_disk_full ${MORAINE_PYTHON})
add_test(NAME robust.permission COMMAND ${MORAINE_ROBUST_DIR}/permission.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_permission)
set_tests_properties(robust.permission PROPERTIES SKIP_RETURN_CODE 77)
add_test(NAME robust.sigterm_twice COMMAND ${MORAINE_ROBUST_DIR}/sigterm_twice.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_sigterm_twice)
add_test(NAME robust.sigint_lua COMMAND ${MORAINE_ROBUST_DIR}/sigint_lua.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_sigint_lua)
set_tests_properties(robust.sigint_lua PROPERTIES LABELS robust ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
add_test(NAME robust.warnings COMMAND ${MORAINE_ROBUST_DIR}/warnings.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_warnings)
add_test(NAME robust.unstable_cfl
         COMMAND $<TARGET_FILE:moraine> ${MORAINE_ROBUST_DIR}/unstable_cfl.lua -q -o ${MORAINE_TEST_OUT}/robust_unstable_cfl)
set_tests_properties(robust.disk_full robust.permission robust.sigterm_twice robust.warnings robust.unstable_cfl
                     PROPERTIES LABELS robust)

# doc/errors.md lists every case above and in tests/bad/ with its message
add_test(NAME doc.errors_table COMMAND ${MORAINE_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/bad/errors_table.py --check
                                       ${CMAKE_SOURCE_DIR}/doc/errors.md)
set_tests_properties(doc.errors_table PROPERTIES LABELS doc)

# The weekly valgrind memcheck (scripts/memcheck.sh, doc/robustness.md): not
# part of ctest; `cmake --build build --target memcheck` builds its own
# valgrind-friendly copy in build/memcheck and runs it.
add_custom_target(memcheck COMMAND ${CMAKE_SOURCE_DIR}/scripts/memcheck.sh ${CMAKE_BINARY_DIR}/memcheck USES_TERMINAL)
