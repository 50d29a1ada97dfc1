#!/usr/bin/env bash
# moraine robustness: a full disk (a file-size limit set with `ulimit -f`).
# case: disk full | the output disk fills up during a run (file-size limit)
# expect: run\{\}: cannot write '.*/part_000005\.vtp': File too large
#
# Checks that moraine
#  - stops with exit status 3 (an output could not be written) and a message
#    naming the file it could not write,
#  - leaves no partial file: neither the failed file nor a temporary one,
#  - keeps every earlier output complete and readable: the VTK snapshots
#    (read back with VTK's own reader), the .pvd index, and the checkpoint
#    (loaded again by moraine).
# usage: disk_full.sh MORAINE OUTDIR PYTHON
set -u
moraine=$1 out=$2 python=$3 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
expect=$(sed -n 's/^# expect: //p' "$0")
limit_kb=256
# moraine ignores SIGXFSZ itself, so write() fails with EFBIG rather than killing it
(ulimit -f $limit_kb; exec "$moraine" "$here/disk_full.lua" -q -o "$out") 2>"$out/stderr.txt"
status=$?
err=$(cat "$out/stderr.txt")
fail=0
[ $status -eq 3 ] || { echo "FAIL: exit status $status, expected 3"; fail=1; }
grep -Eq -- "$expect" <<<"$err" || { echo "FAIL: message does not match /$expect/"; fail=1; }
[ ! -e "$out/part_000005.vtp" ] || { echo "FAIL: the file that could not be written exists"; fail=1; }
leftovers=$(find "$out" -name '.*.tmp.*')
[ -z "$leftovers" ] || { echo "FAIL: temporary files left: $leftovers"; fail=1; }
big=$(find "$out" -type f -size +${limit_kb}k)
[ -z "$big" ] || { echo "FAIL: files above the limit: $big"; fail=1; }
# every earlier output is complete: five snapshots, the index, the time series, the checkpoint
"$python" - "$out" <<'PY' || fail=1
import sys, os, xml.etree.ElementTree as ET
import vtk, h5py
vtk.vtkObject.GlobalWarningDisplayOff()
out = sys.argv[1]
want = [f"part_{i:06d}.vtp" for i in range(5)]  # steps 0, 5, .., 20
ok = True
for name in want:
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(out, name))
    r.Update()
    n = r.GetOutput().GetNumberOfPoints()
    if n != 64:  # 4 x 4 cells x 2 x 2 particles
        print(f"FAIL: {name} has {n} points, expected 64"); ok = False
pvd = ET.parse(os.path.join(out, "part.pvd")).getroot()
listed = [d.get("file") for d in pvd.iter("DataSet")]
for f in listed:
    if not os.path.exists(os.path.join(out, f)):
        print(f"FAIL: part.pvd lists {f}, which does not exist"); ok = False
if listed[:5] != want:
    print(f"FAIL: part.pvd lists {listed}"); ok = False
with h5py.File(os.path.join(out, "diagnostics.h5"), "r") as f:  # the time series, closed cleanly
    print(f"diagnostics.h5 holds {len(f.keys())} groups")
print(f"{len(want)} snapshots and the index read back")
sys.exit(0 if ok else 1)
PY
cat > "$out/reload.lua" <<'LUA'
local sim = mpm.load(mpm.outdir .. "/early.h5")
assert(sim:particle_count() == 64 and sim:step() == 20, "early.h5 holds the wrong state")
print("early.h5 loads: " .. sim:particle_count() .. " particles at step " .. sim:step())
LUA
"$moraine" "$out/reload.lua" -q -o "$out" || { echo "FAIL: early.h5 does not load"; fail=1; }
echo "message: ${err#moraine: }"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
