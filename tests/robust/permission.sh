#!/usr/bin/env bash
# moraine robustness: the output directory is not writable.
# case: permission | the output directory is read-only
# expect: cannot write the lock file '.*/locked/\.moraine\.lock': Permission denied
#
# The run must stop at its first output (the lock file of the directory,
# taken before the deck runs) with exit status 3 and the path and reason, leaving nothing
# behind. moraine runs as an ordinary user: as root the test drops to 'nobody'
# with setpriv (root may write anywhere); it is skipped (status 77) when that
# is not possible.
# usage: permission.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out/locked"
expect=$(sed -n 's/^# expect: //p' "$0")
cp "$here/disk_full.lua" "$out/deck.lua"
chmod 755 "$out"; chmod 644 "$out/deck.lua"; chmod 555 "$out/locked"
run=("$moraine" "$out/deck.lua" -q -o "$out/locked")
if [ "$(id -u)" -eq 0 ]; then
  command -v setpriv >/dev/null || { echo "setpriv not found: skipped"; exit 77; }
  run=(setpriv --reuid=65534 --regid=65534 --clear-groups "${run[@]}")
  "${run[@]:0:4}" test -x "$moraine" -a -r "$out/deck.lua" || { echo "moraine is not reachable as nobody: skipped"; exit 77; }
fi
"${run[@]}" 2>"$out/stderr.txt"
status=$?
err=$(cat "$out/stderr.txt")
fail=0
[ $status -eq 3 ] || { echo "FAIL: exit status $status, expected 3"; fail=1; }
grep -Eq -- "$expect" <<<"$err" || { echo "FAIL: message does not match /$expect/"; fail=1; }
[ -z "$(ls -A "$out/locked")" ] || { echo "FAIL: files were left in the locked directory"; fail=1; }
cat "$out/stderr.txt"
echo "message: ${err#moraine: }"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
