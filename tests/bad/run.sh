#!/usr/bin/env bash
# moraine bad-input test: run a deck that must fail and check
#  - the exit status is non-zero (exactly N when the deck has a line
#    "-- status: N" among its first lines),
#  - stderr matches the regex on the deck's first line ("-- expect: REGEX"),
#  - no temporary (half-written) file is left in the output directory, and
#    every .vtp there is a complete XML document.
# A line "-- options: ..." among the deck's first lines adds those
# command-line options (e.g. --safe).
# usage: run.sh MORAINE DECK OUTDIR
set -u
moraine=$1 deck=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
expect=$(head -n 1 "$deck" | sed -n 's/^-- expect: //p')
options=$(head -n 5 "$deck" | sed -n 's/^-- options: //p')
want=$(head -n 5 "$deck" | sed -n 's/^-- status: //p')
# shellcheck disable=SC2086 # the options are words
err=$("$moraine" "$deck" -q -o "$out" $options 2>&1 >/dev/null)
status=$?
fail=0
if [ $status -eq 0 ]; then echo "FAIL: exit status 0, expected non-zero"; fail=1; fi
if [ -n "$want" ] && [ $status -ne "$want" ]; then echo "FAIL: exit status $status, expected $want"; fail=1; fi
if ! grep -Eq -- "$expect" <<<"$err"; then echo "FAIL: message does not match /$expect/"; fail=1; fi
leftovers=$(find "$out" -name '.*.tmp.*' | head -n 5)
if [ -n "$leftovers" ]; then echo "FAIL: temporary files left: $leftovers"; fail=1; fi
for f in $(find "$out" -name '*.vtp' -o -name '*.pvd'); do
  tail -c 64 "$f" | grep -q '</VTKFile>' || { echo "FAIL: incomplete file $f"; fail=1; }
done
echo "message: $err"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
