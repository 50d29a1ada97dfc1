#!/usr/bin/env bash
# moraine: distributed runs that go wrong, or nearly, on 3 processes
# (tests/parallel/robust.lua): a block crossing two slabs in one step with
# two processes empty, a particle leaving the grid (stopping the run, or
# deleted with its energy booked as outflow), a Lua error on one
# process, a grid too thin for the processes, CPDI domains grown too wide
# for the slabs, and SIGINT to mpirun. Each must end (no hang: every run
# has a time limit) with its message once and, where the state is kept,
# one checkpoint.
# usage: robust.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
mpirun="$here/../../scripts/mpirun"
deck="$here/robust.lua"
rm -rf "$out"; mkdir -p "$out"
fail=0
say() { echo "$*"; }
bad() { echo "FAIL: $*"; fail=1; }

# the runs that end with an error need no grace time after it (scripts/mpirun)
run3() { # case
  local c=$1
  MORAINE_MPI_STOP_SECONDS=1 OMP_NUM_THREADS=1 timeout 300 "$mpirun" -np 3 "$moraine" -q --overwrite -o "$out/$c" --set case=$c "$deck" \
    >"$out/$c.out" 2>&1
}

# crossing: passes its own checks (mass, momentum, position, who holds the particles)
run3 crossing; s=$?
[ $s -eq 0 ] || { bad "crossing exited $s"; cat "$out/crossing.out"; }
grep -q "cuts 0 4 8 12" "$out/crossing.out" || bad "crossing: not cut into three slabs of 4 cells"
say "crossing: exit $s; $(grep -c 'holds' "$out/crossing.out") line(s) of process 0's report"

# leave: the diagnosis once, one checkpoint, every process stopped
run3 leave; s=$?
[ $s -ne 0 ] || bad "leave exited 0"
n=$(grep -c "left the grid" "$out/leave.out")
[ "$n" -eq 1 ] || { bad "leave: the diagnosis printed $n times"; cat "$out/leave.out"; }
[ -s "$out/leave/leave_failed.h5" ] || bad "leave: no checkpoint leave_failed.h5"
say "leave: exit $s; $(grep -o 'particle [0-9]* left the grid[^;]*' "$out/leave.out" | head -1)"

# outflow: deleted where it is, booked by every process, summed once
run3 outflow; s=$?
[ $s -eq 0 ] || { bad "outflow exited $s"; cat "$out/outflow.out"; }
say "outflow: exit $s; $(grep -o 'outflow: .*' "$out/outflow.out")"

# lua_error: the last process's hook fails; all stop with its message once, and the state is kept
run3 lua_error; s=$?
[ $s -ne 0 ] || bad "lua_error exited 0"
n=$(grep -c "the last process gives up at step 20" "$out/lua_error.out")
[ "$n" -eq 1 ] || { bad "lua_error: the message printed $n times"; cat "$out/lua_error.out"; }
[ -s "$out/lua_error/lua_error_failed.h5" ] || bad "lua_error: no checkpoint lua_error_failed.h5"
say "lua_error: exit $s; $(grep -o 'the last process gives up[^;]*; the state at step [0-9]*' "$out/lua_error.out")"

# small_grid: refused with the numbers, once
run3 small_grid; s=$?
[ $s -ne 0 ] || bad "small_grid exited 0"
expect="parallel: 3 processes need at least 12 cells along y (4 per process); the grid has 8"
n=$(grep -c -F "$expect" "$out/small_grid.out")
[ "$n" -eq 1 ] || { bad "small_grid: the message printed $n times"; cat "$out/small_grid.out"; }
say "small_grid: exit $s; $expect"

# cpdi_thin: stopped when the domains outgrow the slabs, with the numbers, once
run3 cpdi_thin; s=$?
[ $s -ne 0 ] || bad "cpdi_thin exited 0"
expect="cells from their particles: the halo bands take node rows [cut - 2, cut + 2], and the slabs at least 5 cells (3 at an end of the axis); process 1's slab has 4"
n=$(grep -c -F "$expect" "$out/cpdi_thin.out")
[ "$n" -eq 1 ] || { bad "cpdi_thin: the message printed $n times"; cat "$out/cpdi_thin.out"; }
say "cpdi_thin: exit $s; $(grep -o "parallel: step [0-9]*: CPDI's domains[^:]*" "$out/cpdi_thin.out")"

# sigint: SIGINT to mpirun; every process finishes its step, one checkpoint
# --foreground: timeout passes a signal it gets to mpirun alone (without it,
# also to its whole process group, the processes included, a second SIGINT
# on which mpirun kills them at once)
OMP_NUM_THREADS=1 timeout --foreground 300 "$mpirun" -np 3 "$moraine" -q --overwrite -o "$out/sigint" --set case=sigint \
  "$deck" >"$out/sigint.out" 2>&1 &
pid=$!
for _ in $(seq 1 600); do [ -e "$out/sigint/started" ] && break; sleep 0.05; done
sleep 0.5
kill -INT $pid
wait $pid; s=$?
[ $s -ne 0 ] || bad "sigint exited 0"
n=$(grep -c "interrupted by signal" "$out/sigint.out")
[ "$n" -eq 1 ] || { bad "sigint: the message printed $n times"; cat "$out/sigint.out"; }
[ -s "$out/sigint/sigint_interrupted.h5" ] || bad "sigint: no checkpoint sigint_interrupted.h5"
[ -z "$(find "$out" -name '.*.tmp.*')" ] || bad "temporary files left"
say "sigint: exit $s; $(grep -o 'interrupted by signal [0-9]* after step [0-9]*' "$out/sigint.out")"

if [ $fail -eq 0 ]; then echo "7 passed, 0 failed"; else echo "some failed"; fi
exit $fail
