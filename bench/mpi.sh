#!/usr/bin/env bash
# moraine: distributed runs against one process, in one run (doc/performance.md,
# "Distributed runs"). For each problem of bench/mpi_scaling.lua, in interleaved
# rounds: 1 process x 1 thread, 1 process x 2 threads, 2 processes x 1 thread
# (scripts/mpirun). Prints each run's line, then the medians and the ratios,
# and the weak-scaling projection of bench/mpi_model.py from the measured costs.
#   bench/mpi.sh [--rounds N] [--problems a160k,c32,collapse3d] [--moraine PATH]
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=3 problems="a160k,c32,collapse3d" moraine=build/moraine
while [ $# -gt 0 ]; do
  case $1 in
    --rounds) rounds=$2; shift 2 ;;
    --problems) problems=$2; shift 2 ;;
    --moraine) moraine=$2; shift 2 ;;
    *) echo "bench/mpi.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
[ -x "$moraine" ] || { echo "bench/mpi.sh: build moraine first ($moraine)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
log="$out/lines.txt"
steps_of() { case $1 in a160k) echo 200 ;; c32) echo 30 ;; *) echo 40 ;; esac; }
for r in $(seq 1 "$rounds"); do
  for p in ${problems//,/ }; do
    s=$(steps_of "$p")
    for cfg in "1 1" "1 2" "2 1"; do
      set -- $cfg
      if [ "$1" = 1 ]; then
        OMP_NUM_THREADS=$2 OMP_WAIT_POLICY=PASSIVE "$moraine" -q -o "$out/run" --overwrite --set problem="$p" \
          --set steps="$s" bench/mpi_scaling.lua | tee -a "$log"
      else
        OMP_NUM_THREADS=$2 OMP_WAIT_POLICY=PASSIVE scripts/mpirun -np "$1" "$moraine" -q -o "$out/run" --overwrite \
          --set problem="$p" --set steps="$s" bench/mpi_scaling.lua | tee -a "$log"
      fi
    done
  done
done
# this machine's latency and bandwidth between two processes, for the model
OMP_NUM_THREADS=1 scripts/mpirun -np 2 /usr/bin/python3 bench/mpi_pingpong.py | tee -a "$log"
/usr/bin/python3 bench/mpi_model.py "$log"
