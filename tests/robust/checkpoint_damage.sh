#!/usr/bin/env bash
# moraine robustness: checkpoints with one damaged byte, and older ones without checksums.
# case: files | one damaged byte in a checkpoint's particle values
# expect: load\(\): '.*/ck_vol0\.h5': /particles/vol0 fails its checksum: its values are damaged
#
#  - a byte of one particle's vol0 (its exponent: 0.0025 becomes about 1e180)
#    and a byte of HDF5's metadata: mpm.load refuses each (exit status 1),
#    naming the file and the dataset or the metadata;
#  - the committed checkpoint of format version 1 (no checksums) loads and
#    runs, with one warning naming the file;
#  - the same older file with a damaged byte in its metadata is refused;
#  - a checkpoint whose vol0 was changed with h5py is refused until
#    `moraine --sign-checkpoint` writes its table anew, and then loads with
#    the new values; signing a file without a table is refused;
#  - nothing of HDF5's own printing reaches the terminal in any of them
#    (no error stack, no "infinite loop closing library" at exit).
# usage: checkpoint_damage.sh MORAINE OUTDIR PYTHON
set -u
moraine=$1 out=$2 python=$3 here=$(cd "$(dirname "$0")" && pwd)
older="$here/../fuzz/corpus/checkpoint/valid_2d.h5"
rm -rf "$out"; mkdir -p "$out"
expect=$(sed -n 's/^# expect: //p' "$0")
deck="$here/checkpoint_damage.lua"
fail=0
"$moraine" "$deck" -q -o "$out" 2>"$out/save.txt" || { echo "FAIL: saving the checkpoint: $(cat "$out/save.txt")"; exit 1; }

# damage.py FROM TO OFFSET: a copy with byte OFFSET xor 0x5a; OFFSET "vol0" is
# the exponent byte of particle 3's vol0, found in the file's checksum table
damage() {
  "$python" - "$@" <<'PY'
import re, sys
src, dst, where = sys.argv[1:4]
data = bytearray(open(src, "rb").read())
if where == "vol0":
    table = data[:4096].split(b"\0")[0].decode()
    offset = int(re.search(r"^data \w+ (\d+) \d+ /particles/vol0$", table, re.M).group(1)) + 3 * 8 + 7
else:
    offset = int(where)
data[offset] ^= 0x5A
open(dst, "wb").write(bytes(data))
PY
}

# load FILE STATUS PATTERN: mpm.load with the expected exit status and stderr
load() {
  local file=$1 want=$2 pattern=$3
  "$moraine" "$deck" -q -o "$out" --set file="$file" 2>"$out/stderr.txt" >/dev/null
  local status=$? err
  err=$(cat "$out/stderr.txt")
  [ $status -eq "$want" ] || { echo "FAIL: $file: exit status $status, expected $want: $err"; fail=1; }
  grep -Eq -- "$pattern" <<<"$err" || { echo "FAIL: $file: stderr does not match /$pattern/: $err"; fail=1; }
  ! grep -Eq "HDF5-DIAG|HDF5: " <<<"$err" || { echo "FAIL: $file: HDF5's own printing reached stderr: $err"; fail=1; }
  last=$err
}

damage "$out/ck.h5" "$out/ck_vol0.h5" vol0
load "$out/ck_vol0.h5" 1 "$expect"
message=$(grep 'vol0' <<<"$last" | tail -n 1)
damage "$out/ck.h5" "$out/ck_meta.h5" 4170
load "$out/ck_meta.h5" 1 "'.*/ck_meta\.h5': the HDF5 metadata \(groups, attributes, dataset layouts\) fails its checksum"
load "$older" 0 "warning \[checkpoint_no_checksums\]: '.*valid_2d\.h5' has no checksums \(format version 1"
[ "$(grep -c 'warning' <<<"$last")" -eq 1 ] || { echo "FAIL: the older file gave $(grep -c warning <<<"$last") warnings"; fail=1; }
damage "$older" "$out/older_meta.h5" 74
load "$out/older_meta.h5" 1 "'.*/older_meta\.h5': cannot read the attributes of / \(truncated or corrupted file\)"
# an edit made on purpose with h5py, then signed
cp "$out/ck.h5" "$out/ck_edited.h5"
"$python" -c "import h5py,sys; f=h5py.File(sys.argv[1],'r+'); f['/particles/vol0'][0]*=2; f.close()" "$out/ck_edited.h5"
load "$out/ck_edited.h5" 1 "'.*/ck_edited\.h5': /particles/vol0 fails its checksum"
signed=$("$moraine" --sign-checkpoint "$out/ck_edited.h5" 2>&1) ||
  { echo "FAIL: --sign-checkpoint: $signed"; fail=1; }
load "$out/ck_edited.h5" 0 "^$"
"$python" -c "import h5py,sys; f=h5py.File(sys.argv[1],'r'); v=f['/particles/vol0']; sys.exit(0 if v[0]==2*v[1] else 1)" \
  "$out/ck_edited.h5" || { echo "FAIL: the signed file lost the edit"; fail=1; }
unsigned=$("$moraine" --sign-checkpoint "$older" 2>&1)
[ $? -eq 1 ] && grep -q "valid_2d.h5" <<<"$unsigned" ||
  { echo "FAIL: signing a file without a table: $unsigned"; fail=1; }
echo "message: $(sed 's/^moraine: //' <<<"$message")"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
