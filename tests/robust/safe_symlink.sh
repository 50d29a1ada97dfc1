#!/usr/bin/env bash
# moraine --safe: a symbolic link inside the output directory that leads out.
# case: permission | --safe: a write through a symbolic link in the output directory that leads outside it
# expect: safe_symlink\.lua:7: io\.open\(\): '.*/run/link/stolen\.txt' is outside the output directory '.*/run' \(it resolves to '.*/elsewhere/stolen\.txt'\); --safe allows writes only below the output directory
#
# OUTDIR/run is the output directory; OUTDIR/run/link leads to the directory
# OUTDIR/elsewhere and OUTDIR/run/linked.csv to the file
# OUTDIR/elsewhere/target.csv. Both writes must be refused with exit status
# 1, and OUTDIR/elsewhere must be left as it was.
# usage: safe_symlink.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out/run" "$out/elsewhere"
expect=$(sed -n 's/^# expect: //p' "$0")
echo "kept" >"$out/elsewhere/target.csv"
ln -s ../elsewhere "$out/run/link"
ln -s ../elsewhere/target.csv "$out/run/linked.csv"
fail=0
err=$("$moraine" "$here/safe_symlink.lua" --safe -q -o "$out/run" 2>&1 >/dev/null)
status=$?
[ $status -eq 1 ] || { echo "FAIL: exit status $status, expected 1"; fail=1; }
grep -Eq -- "$expect" <<<"$err" || { echo "FAIL: message does not match /$expect/"; fail=1; }
file_err=$("$moraine" "$here/safe_symlink.lua" --safe -q -o "$out/run" --set through=file 2>&1 >/dev/null)
status=$?
[ $status -eq 1 ] || { echo "FAIL: the linked CSV: exit status $status, expected 1"; fail=1; }
grep -Eq -- "simulation\{\}: diagnostics: '.*/run/linked\.csv' is outside the output directory '.*/run' \(it resolves to '.*/elsewhere/target\.csv'\)" <<<"$file_err" ||
  { echo "FAIL: the linked CSV: $file_err"; fail=1; }
[ "$(ls -A "$out/elsewhere")" = "target.csv" ] && [ "$(cat "$out/elsewhere/target.csv")" = "kept" ] ||
  { echo "FAIL: OUTDIR/elsewhere was written to: $(ls -A "$out/elsewhere")"; fail=1; }
echo "message: ${err#moraine: }"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
