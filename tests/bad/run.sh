#!/usr/bin/env bash
# moraine bad-input test: run a deck that must fail and check
#  - the exit status is non-zero,
#  - stderr matches the regex on the deck's first line ("-- expect: REGEX"),
#  - no temporary (half-written) file is left in the output directory, and
#    every .vtp there is a complete XML document.
# usage: run.sh MORAINE DECK OUTDIR
set -u
moraine=$1 deck=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
expect=$(head -n 1 "$deck" | sed -n 's/^-- expect: //p')
err=$("$moraine" "$deck" -q -o "$out" 2>&1 >/dev/null)
status=$?
fail=0
if [ $status -eq 0 ]; then echo "FAIL: exit status 0, expected non-zero"; fail=1; fi
if ! grep -Eq -- "$expect" <<<"$err"; then echo "FAIL: message does not match /$expect/"; fail=1; fi
leftovers=$(find "$out" -name '.*.tmp.*' | head -n 5)
if [ -n "$leftovers" ]; then echo "FAIL: temporary files left: $leftovers"; fail=1; fi
for f in $(find "$out" -name '*.vtp' -o -name '*.pvd'); do
  tail -c 64 "$f" | grep -q '</VTKFile>' || { echo "FAIL: incomplete file $f"; fail=1; }
done
echo "message: $err"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
