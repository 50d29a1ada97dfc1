# Fuzzing harnesses (tests/fuzz/README.md).
#
# Every build compiles each harness with a small replay main() and runs it in
# the quick suite over its seed corpus plus a few hundred generated inputs, so
# the harnesses cannot rot. With -DMORAINE_FUZZ=ON (clang) the same harnesses
# are also linked with libFuzzer as fuzz_checkpoint and fuzz_deck.
set(MORAINE_FUZZ_DIR ${CMAKE_CURRENT_SOURCE_DIR}/fuzz)
set(MORAINE_FUZZ_HARNESSES checkpoint deck)
set(fuzz_lib_checkpoint moraine_engine)
set(fuzz_lib_deck moraine_lua)

foreach(h ${MORAINE_FUZZ_HARNESSES})
  add_executable(fuzz_replay_${h} ${MORAINE_FUZZ_DIR}/fuzz_${h}.c ${MORAINE_FUZZ_DIR}/replay_main.c)
  target_link_libraries(fuzz_replay_${h} PRIVATE ${fuzz_lib_${h}})
  target_compile_definitions(fuzz_replay_${h} PRIVATE MORAINE_FUZZ_DIR="${MORAINE_FUZZ_DIR}")
  add_test(NAME fuzz.${h}_replay COMMAND fuzz_replay_${h} -n 300 ${MORAINE_FUZZ_DIR}/corpus/${h})
  # under the sanitizers: HDF5's own leaks on corrupted files are not moraine's (lsan.supp)
  set_tests_properties(fuzz.${h}_replay PROPERTIES LABELS fuzz ENVIRONMENT
                       "OMP_NUM_THREADS=1;LSAN_OPTIONS=suppressions=${MORAINE_FUZZ_DIR}/lsan.supp")
  if(MORAINE_FUZZ)
    add_executable(fuzz_${h} ${MORAINE_FUZZ_DIR}/fuzz_${h}.c)
    target_link_libraries(fuzz_${h} PRIVATE ${fuzz_lib_${h}})
    target_compile_definitions(fuzz_${h} PRIVATE MORAINE_FUZZ_DIR="${MORAINE_FUZZ_DIR}")
    target_link_options(fuzz_${h} PRIVATE -fsanitize=fuzzer)
  endif()
endforeach()

# The long runs (doc/robustness.md, "The runs"): both harnesses side by side
# for MORAINE_FUZZ_SECONDS each (default 1800), new inputs and any finding in
# BUILD_DIR/fuzz-work. Not part of ctest:
#   cmake --build build-fuzz --target fuzz_long
if(MORAINE_FUZZ)
  set(MORAINE_FUZZ_SECONDS 1800 CACHE STRING "seconds each harness runs under the fuzz_long target")
  add_custom_target(fuzz_long
                    COMMAND ${MORAINE_FUZZ_DIR}/run_long.sh ${CMAKE_BINARY_DIR} ${MORAINE_FUZZ_SECONDS}
                            ${CMAKE_BINARY_DIR}/fuzz-work
                    DEPENDS fuzz_checkpoint fuzz_deck USES_TERMINAL)
endif()
