#!/usr/bin/env bash
# moraine robustness: a second signal exits at once.
# case: signals | SIGTERM twice: the second does not wait for the step to finish
# expect: second signal, exiting at once
#
# The first SIGTERM asks the run to stop after the current step; the step is
# held up by a slow hook, so a second SIGTERM must end moraine at once, with
# exit status 130, within a second and without leaving a temporary file.
# usage: sigterm_twice.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
expect=$(sed -n 's/^# expect: //p' "$0")
"$moraine" "$here/sigterm_twice.lua" -q -o "$out" 2>"$out/stderr.txt" &
pid=$!
for _ in $(seq 1 600); do [ -e "$out/started" ] && break; sleep 0.05; done
kill -TERM $pid
sleep 0.2
start=$(date +%s%N)
kill -TERM $pid
wait $pid
status=$?
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
err=$(cat "$out/stderr.txt")
fail=0
[ $status -eq 130 ] || { echo "FAIL: exit status $status, expected 130"; fail=1; }
grep -Eq -- "$expect" <<<"$err" || { echo "FAIL: message does not match /$expect/"; fail=1; }
[ $elapsed_ms -lt 1000 ] || { echo "FAIL: took $elapsed_ms ms after the second signal"; fail=1; }
[ -z "$(find "$out" -name '.*.tmp.*')" ] || { echo "FAIL: temporary files left"; fail=1; }
echo "message: $(tail -n 1 <<<"$err" | sed 's/^moraine: //')"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
