#!/usr/bin/env bash
# moraine robustness: warnings for legal but suspicious choices, and silencing them.
# case: warnings | a fixed dt above the CFL estimate, a Courant number above 1, one particle per cell
# expect: warning \[dt_above_cfl\]: the fixed time step .* is 1\.5 times the CFL estimate
#
#  - each kind is printed once, with its ID and how to silence it, and the run
#    goes on (exit status 0);
#  - --ignore-warning ID and mpm.warnings{ignore = {ID}} silence one kind,
#    --ignore-warning all every kind;
#  - an unknown ID is a command-line error (status 2).
# usage: warnings.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
expect=$(sed -n 's/^# expect: //p' "$0")
deck="$here/warnings.lua"
fail=0
count() { grep -c "warning \[$1\]" <<<"$2"; }
err=$("$moraine" "$deck" -q -o "$out" 2>&1 >/dev/null) || { echo "FAIL: the run with warnings failed: $err"; fail=1; }
for id in dt_above_cfl courant_above_one one_particle_per_cell; do
  [ "$(count $id "$err")" -eq 1 ] || { echo "FAIL: [$id] printed $(count $id "$err") times, expected once"; fail=1; }
done
grep -Eq -- "$expect" <<<"$err" || { echo "FAIL: message does not match /$expect/"; fail=1; }
grep -q 'silence: mpm.warnings{ignore = {"dt_above_cfl"}} or --ignore-warning dt_above_cfl' <<<"$err" ||
  { echo "FAIL: the warning does not say how to silence it"; fail=1; }
quiet=$("$moraine" "$deck" -q -o "$out" --ignore-warning dt_above_cfl 2>&1 >/dev/null)
[ "$(count dt_above_cfl "$quiet")" -eq 0 ] && [ "$(count courant_above_one "$quiet")" -eq 1 ] ||
  { echo "FAIL: --ignore-warning dt_above_cfl: $quiet"; fail=1; }
quiet=$("$moraine" "$deck" -q -o "$out" --set silence=one_particle_per_cell 2>&1 >/dev/null)
[ "$(count one_particle_per_cell "$quiet")" -eq 0 ] && [ "$(count dt_above_cfl "$quiet")" -eq 1 ] ||
  { echo "FAIL: mpm.warnings{ignore = {\"one_particle_per_cell\"}}: $quiet"; fail=1; }
quiet=$("$moraine" "$deck" -q -o "$out" --ignore-warning all 2>&1 >/dev/null)
[ -z "$quiet" ] || { echo "FAIL: --ignore-warning all still printed: $quiet"; fail=1; }
"$moraine" "$deck" -q -o "$out" --ignore-warning dt_abov_cfl 2>/dev/null
[ $? -eq 2 ] || { echo "FAIL: an unknown warning ID is not a command-line error"; fail=1; }
echo "message: $(grep 'dt_above_cfl' <<<"$err" | head -n 1 | sed 's/^moraine: //')"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
