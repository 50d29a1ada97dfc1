# Robustness tests of tests/robust/ added for bad outputs, signals, unstable
# runs and warnings (doc/errors.md lists them with the message each shows).
set(MORAINE_ROBUST_DIR ${CMAKE_CURRENT_SOURCE_DIR}/robust)
add_test(NAME robust.disk_full
         COMMAND ${MORAINE_ROBUST_DIR}/disk_full.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_disk_full ${Python3_EXECUTABLE})
add_test(NAME robust.permission COMMAND ${MORAINE_ROBUST_DIR}/permission.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_permission)
set_tests_properties(robust.permission PROPERTIES SKIP_RETURN_CODE 77)
add_test(NAME robust.sigterm_twice COMMAND ${MORAINE_ROBUST_DIR}/sigterm_twice.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_sigterm_twice)
add_test(NAME robust.sigint_lua COMMAND ${MORAINE_ROBUST_DIR}/sigint_lua.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_sigint_lua)
set_tests_properties(robust.sigint_lua PROPERTIES LABELS robust ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
add_test(NAME robust.warnings COMMAND ${MORAINE_ROBUST_DIR}/warnings.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_warnings)
# long options, a deck on stdin, the warning about a --set never read
add_test(NAME robust.cli COMMAND ${MORAINE_ROBUST_DIR}/cli.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_cli)
add_test(NAME robust.unstable_cfl
         COMMAND $<TARGET_FILE:moraine> ${MORAINE_ROBUST_DIR}/unstable_cfl.lua -q -o ${MORAINE_TEST_OUT}/robust_unstable_cfl --overwrite)
# every output file failing once (tests/robust/faults.py): faultfs, the LD_PRELOAD
# library that injects the faults, goes next to moraine, where faults.py looks.
# It is built without the sanitizers: a sanitised program wants their runtime
# first among its libraries, and faultfs is preloaded before it.
add_library(faultfs MODULE ${MORAINE_ROBUST_DIR}/faultfs.c)
set_target_properties(faultfs PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR} COMPILE_OPTIONS "-Wall;-Wextra" LINK_OPTIONS "")
target_link_libraries(faultfs PRIVATE ${CMAKE_DL_LIBS})
add_test(NAME robust.faults
         COMMAND ${MORAINE_ROBUST_DIR}/faults.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_faults ${Python3_EXECUTABLE})
# the physical-sanity watchdog: an explosive run pinned to the walls stops;
# violent runs that are right (bouncing cube, dam break) keep far from its bounds
add_test(NAME robust.watchdog
         COMMAND $<TARGET_FILE:moraine> ${MORAINE_ROBUST_DIR}/watchdog.lua -q -o ${MORAINE_TEST_OUT}/robust_watchdog --overwrite)
add_test(NAME robust.watchdog_legit
         COMMAND $<TARGET_FILE:moraine> ${MORAINE_ROBUST_DIR}/watchdog_legit.lua -q -o ${MORAINE_TEST_OUT}/robust_watchdog_legit --overwrite)
# one damaged byte in a checkpoint, older checkpoints without checksums, no HDF5 printing
add_test(NAME robust.checkpoint_damage
         COMMAND ${MORAINE_ROBUST_DIR}/checkpoint_damage.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_checkpoint_damage ${Python3_EXECUTABLE})
set_tests_properties(robust.disk_full robust.permission robust.sigterm_twice robust.warnings robust.cli robust.unstable_cfl
                     robust.watchdog robust.watchdog_legit robust.checkpoint_damage robust.faults PROPERTIES LABELS robust)

# --safe (doc/security.md): the refusals are tests/bad/safe_*.lua; these check
# a link leading out, what a deck may still do, and an example that runs as usual
add_test(NAME robust.safe_symlink COMMAND ${MORAINE_ROBUST_DIR}/safe_symlink.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_safe_symlink)
add_test(NAME robust.safe_allowed
         COMMAND $<TARGET_FILE:moraine> ${MORAINE_ROBUST_DIR}/safe_allowed.lua --safe -q -o ${MORAINE_TEST_OUT}/robust_safe_allowed --overwrite)
add_test(NAME robust.safe_example COMMAND ${MORAINE_ROBUST_DIR}/safe_example.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_safe_example)
set_tests_properties(robust.safe_symlink robust.safe_allowed robust.safe_example PROPERTIES LABELS robust)

# doc/errors.md lists every case above and in tests/bad/ with its message
add_test(NAME doc.errors_table COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/bad/errors_table.py --check
                                       ${CMAKE_SOURCE_DIR}/doc/errors.md)
set_tests_properties(doc.errors_table PROPERTIES LABELS doc)

# The weekly valgrind memcheck (scripts/memcheck.sh, doc/robustness.md): not
# part of ctest; `cmake --build build --target memcheck` builds its own
# valgrind-friendly copy in build/memcheck and runs it.
add_custom_target(memcheck COMMAND ${CMAKE_SOURCE_DIR}/scripts/memcheck.sh ${CMAKE_BINARY_DIR}/memcheck USES_TERMINAL)
# a run stopped at a random step (SIGINT, SIGKILL) and continued with
# --restart leaves a straight run's outputs; refused second and concurrent runs
add_test(NAME robust.resume COMMAND ${MORAINE_ROBUST_DIR}/resume.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/robust_resume ${Python3_EXECUTABLE})
set_tests_properties(robust.resume PROPERTIES LABELS robust ENVIRONMENT OMP_WAIT_POLICY=PASSIVE TIMEOUT 120)
# an inflow source continued with --restart: its progress from /sources, bit for bit
add_test(NAME robust.source_restart COMMAND ${MORAINE_ROBUST_DIR}/source_restart.sh $<TARGET_FILE:moraine>
                                            ${MORAINE_TEST_OUT}/robust_source_restart ${Python3_EXECUTABLE})
set_tests_properties(robust.source_restart PROPERTIES LABELS robust ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
# contact between bodies: the deck's bodies and pairs carried over a --restart, bit for bit
add_test(NAME robust.contact_restart COMMAND ${MORAINE_ROBUST_DIR}/contact_restart.sh $<TARGET_FILE:moraine>
                                             ${MORAINE_TEST_OUT}/robust_contact_restart ${Python3_EXECUTABLE})
set_tests_properties(robust.contact_restart PROPERTIES LABELS robust ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
