#!/usr/bin/env bash
# moraine: set up, build and run the whole test suite (the README's test command).
#   scripts/test.sh            release build in build/, then ctest
#   scripts/test.sh --sanitize also an AddressSanitizer + UBSan build in build-asan/
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=0
[ "${1:-}" = "--sanitize" ] && sanitize=1

scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMORAINE_NATIVE=ON
cmake --build build -j "$jobs"
(cd build && ctest --output-on-failure -j "$jobs")

if [ "$sanitize" = 1 ]; then
  # the sanitised build is also the one-process build without MPI: both builds are tested
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMORAINE_SANITIZE=ON -DMORAINE_MPI=OFF
  cmake --build build-asan -j "$jobs"
  # the suite again, sanitised; tests labelled "long" or "slow" (minute-long physics runs
  # whose code paths the shorter tests cover) are left to the release pass
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
     ctest --output-on-failure -j "$jobs" -LE "long|slow")
fi
