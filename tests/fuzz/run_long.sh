#!/usr/bin/env bash
# moraine: run both libFuzzer harnesses side by side (one core each) for the
# same time and report each one's executions and outcome.
#
#   tests/fuzz/run_long.sh BUILD_DIR SECONDS WORK_DIR
#
# The logs are WORK_DIR/HARNESS.log; the exit status is the number of
# harnesses that stopped on a finding (its input is WORK_DIR/HARNESS-*).
set -uo pipefail
build=$1 seconds=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
pids=()
for h in checkpoint deck; do
  "$here/run.sh" "$build" "$h" "$seconds" "$work" > "$work/$h.log" 2>&1 &
  pids+=($!)
done
failed=0 i=0
for h in checkpoint deck; do
  wait "${pids[$i]}" || failed=$((failed + 1))
  i=$((i + 1))
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$h.log" | tail -n 1)
  if grep -Eq 'ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)|SUMMARY: ' "$work/$h.log"; then
    echo "$h: FINDING after ${runs:-?} executions (see $work/$h.log)"
  else
    echo "$h: clean, ${runs:-?} executions in $seconds s"
  fi
done
exit $failed
