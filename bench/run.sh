#!/bin/sh
# Build moraine's benchmark harness in Release mode for this machine
# (-DMORAINE_NATIVE=ON: -march=native, off in a default build) and run it
# against the speed anchors.
#
#   bench/run.sh [bench options...]      e.g. bench/run.sh --only a,c --reps 5
#
# BUILD_DIR (default: build-bench next to this directory's parent) is the
# build directory; ANCHORS (default: ../shared/anchors from the source tree)
# holds ref2d.c and ref3d.c. Results: a table on stdout and bench-results.json
# in the current directory (--json FILE to change).
set -e
src=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$src/build-bench}
anchors=${ANCHORS:-$src/../shared/anchors}
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DMORAINE_TESTS=OFF -DMORAINE_NATIVE=ON -DMORAINE_MAN=OFF > /dev/null
cmake --build "$build" --target bench -j "$(nproc 2>/dev/null || echo 2)" > /dev/null
if [ -f "$anchors/ref2d.c" ] && [ -f "$anchors/ref3d.c" ]; then
  exec "$build/moraine-bench" --anchors "$anchors" "$@"
else
  echo "bench/run.sh: no anchors in $anchors; running without them" >&2
  exec "$build/moraine-bench" "$@"
fi
