#!/usr/bin/env bash
# moraine: SIGINT during a run leaves a checkpoint from which mpm.load continues
# bit for bit to the same final state as an uninterrupted run.
# case: signals | SIGINT during a run: checkpoint, exit 130, bitwise continuation
# expect: run\{\}: interrupted by signal 2 after step [0-9]+ .*; the state at step [0-9]+ is in .*/sig_interrupted\.h5
# usage: sigint.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
steps=60000
rm -rf "$out"; mkdir -p "$out"
"$moraine" "$here/sigint_run.lua" -q -o "$out" --set steps=$steps 2>"$out/stderr.txt" &
pid=$!
for _ in $(seq 1 600); do [ -e "$out/started" ] && break; sleep 0.05; done
sleep 0.3
kill -INT $pid
wait $pid
status=$?
fail=0
[ $status -eq 130 ] || { echo "FAIL: exit status $status, expected 130"; cat "$out/stderr.txt"; fail=1; }
[ -s "$out/sig_interrupted.h5" ] || { echo "FAIL: no checkpoint sig_interrupted.h5"; fail=1; }
grep -q "interrupted by signal 2" "$out/stderr.txt" || { echo "FAIL: message"; cat "$out/stderr.txt"; fail=1; }
if [ -z "$(find "$out" -name '.*.tmp.*')" ]; then :; else echo "FAIL: temporary files left"; fail=1; fi
if [ $fail -eq 0 ]; then
  "$moraine" "$here/sigint_check.lua" -q -o "$out" --set steps=$steps || fail=1
fi
cat "$out/stderr.txt"
expect=$(sed -n 's/^# expect: //p' "$0")
grep -Eq -- "$expect" "$out/stderr.txt" || { echo "FAIL: message does not match /$expect/"; fail=1; }
echo "message: $(grep 'interrupted by signal' "$out/stderr.txt" | sed 's/^moraine: //')"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
