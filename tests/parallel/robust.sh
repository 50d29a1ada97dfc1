#!/usr/bin/env bash
# moraine: distributed runs that go wrong, or nearly, on 3 processes
# (tests/parallel/robust.lua): a block crossing two slabs in one step with
# two processes empty, a particle leaving the grid (stopping the run, or
# deleted with its energy booked as outflow), a Lua error on one
# process, the deck's own files, a grid too thin for the processes, CPDI
# domains grown too wide for the slabs, and SIGINT to mpirun. Each must end
# (no hang: every run has a time limit) with its message once and, where
# the state is kept, one checkpoint.
# The crossing's VTK series, a piece per process, two of them empty at each
# snapshot, is read back with ParaView's reader (check_vtk.py); so are the
# leave case's gathered series (output{gather = true}) and a series saved on
# 3 processes and continued on 2 from an earlier checkpoint.
# usage: robust.sh MORAINE OUTDIR [PYTHON]
set -u
moraine=$1 out=$2 py=${3:-/usr/bin/python3} here=$(cd "$(dirname "$0")" && pwd)
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
"$py" "$here/check_vtk.py" --series "$out/crossing" crossing 8 --empty >"$out/crossing_vtk.out" 2>&1 ||
  { bad "crossing: its VTK series"; cat "$out/crossing_vtk.out"; }
say "crossing: VTK series: $(grep -c 'particles in pieces' "$out/crossing_vtk.out") snapshot(s) read, each particle once"

# leave: the diagnosis once, one checkpoint, every process stopped
run3 leave; s=$?
[ $s -ne 0 ] || bad "leave exited 0"
n=$(grep -c "left the grid" "$out/leave.out")
[ "$n" -eq 1 ] || { bad "leave: the diagnosis printed $n times"; cat "$out/leave.out"; }
[ -s "$out/leave/leave_failed.h5" ] || bad "leave: no checkpoint leave_failed.h5"
say "leave: exit $s; $(grep -o 'particle [0-9]* left the grid[^;]*' "$out/leave.out" | head -1)"
# its series (output{gather = true}): one .vtp per snapshot, the last one written on the failure
[ -z "$(find "$out/leave" -name '*.pvtp')" ] || bad "leave: a gathered series holds .pvtp files"
"$py" "$here/check_vtk.py" --series "$out/leave" leave 8 >"$out/leave_vtk.out" 2>&1 ||
  { bad "leave: its gathered VTK series"; cat "$out/leave_vtk.out"; }
say "leave: gathered VTK series: $(grep -c 'one file' "$out/leave_vtk.out") .vtp snapshot(s) read"

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

# files: the deck's own writes happen once (process 0), and on every process when asked
run3 files; s=$?
[ $s -eq 0 ] || { bad "files exited $s"; cat "$out/files.out"; }
[ "$(cat "$out/files/once.txt" 2>/dev/null)" = "$(printf 'rank 0\nagain rank 0')" ] ||
  { bad "files: once.txt holds:"; cat "$out/files/once.txt"; }
[ "$(cat "$out/files/output.txt" 2>/dev/null)" = "io.output rank 0" ] || bad "files: output.txt is not process 0's alone"
[ ! -e "$out/files/gone.txt" ] || bad "files: os.remove left gone.txt"
for r in 0 1 2; do [ "$(cat "$out/files/every_$r.txt" 2>/dev/null)" = "rank $r" ] || bad "files: every_$r.txt"; done
say "files: exit $s; once.txt, output.txt from process 0 alone, every_0..2.txt from each"

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

# vtk_resume: 40 steps on 3 processes, a snapshot every 10, checkpoints at 15 and 30; continued on 2
# processes from the one at 15: the 3 later snapshots (their .pvtp and 3 pieces each) are replaced
run3 vtk_resume; s=$?
[ $s -eq 0 ] || { bad "vtk_resume exited $s"; cat "$out/vtk_resume.out"; }
OMP_NUM_THREADS=1 timeout 300 "$mpirun" -np 2 "$moraine" -q -o "$out/vtk_resume" \
  --restart "$out/vtk_resume/vtk_resume_checkpoint_0000000015.h5" --set case=vtk_resume "$deck" \
  >"$out/vtk_resume_2.out" 2>&1 || { bad "vtk_resume: the continuation on 2 processes failed"; cat "$out/vtk_resume_2.out"; }
"$py" "$here/check_vtk.py" --series "$out/vtk_resume" vtk_resume 864 >"$out/vtk_resume_vtk.out" 2>&1 ||
  { bad "vtk_resume: its VTK series"; cat "$out/vtk_resume_vtk.out"; }
say "vtk_resume: $(grep -c 'particles in pieces' "$out/vtk_resume_vtk.out") snapshot(s) read; pieces $(grep -o '\[[0-9, ]*\]' "$out/vtk_resume_vtk.out" | tr '\n' ' ')"

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

if [ $fail -eq 0 ]; then echo "9 passed, 0 failed"; else echo "some failed"; fi
exit $fail
