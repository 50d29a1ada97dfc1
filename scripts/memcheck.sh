#!/usr/bin/env bash
# moraine: the weekly valgrind memcheck target (doc/robustness.md).
#
#   scripts/memcheck.sh [BUILD_DIR]        (default: build-memcheck)
#   cmake --build build --target memcheck  (the same, into BUILD/memcheck)
#
# Builds moraine for valgrind (no -march=native, whose AVX-512 valgrind cannot
# decode; no OpenMP, whose thread pool valgrind reports as possibly lost;
# debug information for the stacks) and runs under
#   valgrind --leak-check=full --errors-for-leak-kinds=definite,indirect
# every C unit test, a set of short decks, every bad-input deck of tests/bad
# (each stops on an error: the error paths must not leak either) and the two
# fuzzing harnesses replaying their corpus. A memory error or a definite or
# indirect leak fails the case; the summary lists them and the exit status is
# the number of failed cases (0: clean). Takes about an hour (the decks are
# the long part; MEMCHECK_DECKS="free_fall" makes it about 15 minutes).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build-memcheck}
log=$build/memcheck-logs
command -v valgrind >/dev/null || { echo "memcheck: valgrind is not installed (scripts/install-deps.sh)"; exit 2; }
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMORAINE_NATIVE=OFF -DMORAINE_OPENMP=OFF >/dev/null &&
  cmake --build "$build" -j"$(nproc)" >/dev/null || { echo "memcheck: the build failed"; exit 2; }
rm -rf "$log"; mkdir -p "$log"
vg=(valgrind --quiet --leak-check=full --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect
    --error-exitcode=99 --num-callers=30)
pass=0 failed=()
# one case: NAME EXPECTED_STATUS COMMAND...; fails on valgrind's status 99 or a wrong status
run() {
  local name=$1 want=$2; shift 2
  "${vg[@]}" --log-file="$log/$name.valgrind" "$@" >"$log/$name.out" 2>&1
  local status=$?
  if [ $status -eq 99 ] || { [ "$want" = 0 ] && [ $status -ne 0 ]; } || { [ "$want" = fail ] && [ $status -eq 0 ]; }; then
    failed+=("$name (status $status, see $log/$name.valgrind)")
  else
    pass=$((pass + 1))
  fi
}
for t in "$build"/tests/test_*; do [ -x "$t" ] && run "unit.$(basename "$t")" 0 "$t"; done
# under valgrind a deck runs about 50 times slower: MEMCHECK_DECKS="free_fall" for a quicker pass
read -r -a decks <<<"${MEMCHECK_DECKS:-free_fall lithostatic rotating_disk simple_shear settling checkpoint_workflow vtk_output series_output}"
for d in "${decks[@]}"; do
  run "deck.$d" 0 "$build/moraine" "$here/tests/decks/$d.lua" -q -o "$log/out-$d"
done
for d in "$here"/tests/bad/*.lua; do
  n=$(basename "$d" .lua)
  run "bad.$n" fail "$build/moraine" "$d" -q -o "$log/out-bad-$n"
done
run robust.unstable_cfl 0 "$build/moraine" "$here/tests/robust/unstable_cfl.lua" -q -o "$log/out-unstable-cfl"
for h in checkpoint deck; do
  run "fuzz.$h" 0 "$build/tests/fuzz_replay_$h" -n 30 "$here/tests/fuzz/corpus/$h"
done
echo "memcheck: $pass clean, ${#failed[@]} failed (logs in $log)"
for f in "${failed[@]}"; do echo "  FAIL $f"; done
exit ${#failed[@]}
