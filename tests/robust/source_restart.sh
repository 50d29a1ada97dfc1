#!/usr/bin/env bash
# moraine: an inflow source's progress survives --restart bit for bit. A
# straight run writes checkpoints at steps 200, 400 and 600; a copy of its
# directory, cut back to the checkpoint of step 200, is continued with
# --restart (the deck adds the source again, the checkpoint's /sources gives
# it its progress), and its checkpoint of step 600 must equal the straight
# run's object by object (scripts/bitwise/compare.py: every dataset and
# attribute but /resume and the writer's version).
# usage: source_restart.sh MORAINE OUTDIR [PYTHON]
set -u
moraine=$1 out=$2 py=${3:-/usr/bin/python3}
here=$(cd "$(dirname "$0")" && pwd)
deck=$here/source_restart.lua
rm -rf "$out"; mkdir -p "$out"
"$moraine" "$deck" -q -o "$out/straight" || { echo "FAIL: the straight run failed"; exit 1; }
cp -r "$out/straight" "$out/restart"
rm -f "$out/restart/channel_checkpoint_0000000400.h5" "$out/restart/channel_checkpoint_0000000600.h5"
"$moraine" "$deck" -q -o "$out/restart" --restart "$out/restart/channel_checkpoint_0000000200.h5" ||
  { echo "FAIL: the restart failed"; exit 1; }
mkdir -p "$out/a" "$out/b"
cp "$out/straight/channel_checkpoint_0000000600.h5" "$out/a/"
cp "$out/restart/channel_checkpoint_0000000600.h5" "$out/b/" || { echo "FAIL: the restart wrote no step 600"; exit 1; }
"$py" "$here/../../scripts/bitwise/compare.py" "$out/a" "$out/b" || { echo "FAIL: step 600 differs"; exit 1; }
"$py" - "$out/a/channel_checkpoint_0000000600.h5" <<'PY' || exit 1
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    s = f["sources/0"].attrs
    assert s["name"].decode() == "inlet" and s["layers"] > 0, "no source state in the checkpoint"
    print("ok: source 'inlet' at step 600: progress %.6g m, %d layers, %d particles" %
          (s["progress"], s["layers"], s["particles"]))
PY
echo "ok: --restart from step 200 ends at step 600 bit for bit as the straight run"
