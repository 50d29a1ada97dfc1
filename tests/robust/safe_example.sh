#!/usr/bin/env bash
# moraine --safe: a normal example deck runs as without it and writes only
# inside its output directory.
#  - examples/colliding_disks (quick) exits 0 under --safe;
#  - OUTDIR/run holds its VTK series, diagnostics CSV and HDF5 series and
#    the provenance, every .vtp complete;
#  - nothing but OUTDIR/run appears in OUTDIR.
# usage: safe_example.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
fail=0
"$moraine" "$here/../../examples/colliding_disks/deck.lua" --safe -q -o "$out/run" --set quick=true ||
  { echo "FAIL: exit status $?, expected 0"; fail=1; }
for f in disks.pvd disks_000000.vtp disks_000004.vtp diagnostics.csv diagnostics.h5 provenance/run.txt; do
  [ -s "$out/run/$f" ] || { echo "FAIL: $out/run/$f is missing or empty"; fail=1; }
done
for f in "$out"/run/*.vtp; do
  tail -c 64 "$f" | grep -q '</VTKFile>' || { echo "FAIL: incomplete file $f"; fail=1; }
done
[ "$(ls -A "$out")" = "run" ] || { echo "FAIL: files outside the output directory: $(ls -A "$out")"; fail=1; }
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
