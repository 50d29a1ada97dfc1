#!/usr/bin/env bash
# moraine: SIGKILL at random moments of a run that writes large .vtp/.vti/.pvd,
# an HDF5 series, a CSV and checkpoints all the time; every file left must be
# complete and readable, or absent (check_killed_outputs.py). Hidden temporary
# files (.NAME.tmp.PID) may remain and are ignored by name.
# usage: sigkill.sh MORAINE OUTDIR [KILLS [PYTHON]]
set -u
moraine=$1 out=$2 kills=${3:-12} python=${4:-python3} here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
RANDOM=6 # the same delays every time
dirs=()
for i in $(seq 1 "$kills"); do
  dir="$out/kill_$i"
  "$moraine" "$here/sigkill_writer.lua" -q -o "$dir" 2>"$out/stderr_$i.txt" &
  pid=$!
  for _ in $(seq 1 400); do [ -e "$dir/started" ] && break; sleep 0.02; done
  delay=$(printf "%d.%03d" $((RANDOM % 2)) $((RANDOM % 1000))) # 0 to 2 s into the writing
  sleep "$delay"
  kill -KILL $pid
  wait $pid 2>/dev/null
  status=$?
  [ $status -eq 137 ] || { echo "FAIL: run $i ended with status $status before the kill"; cat "$out/stderr_$i.txt"; exit 1; }
  echo "run $i: killed after $delay s of writing: $(ls "$dir" | wc -l) files"
  dirs+=("$dir")
done
"$python" "$here/check_killed_outputs.py" "${dirs[@]}"
status=$?
[ $status -eq 0 ] && rm -rf "$out"/kill_* # several GB
exit $status
