#!/usr/bin/env bash
# moraine: contact between bodies survives --restart bit for bit. The deck
# saves between its two runs; the restart from that checkpoint takes the
# deck's bodies and contact pairs (the checkpoint holds each particle's body
# index and the nodes where the contact held) and must end on the same state
# line, digit for digit.
# usage: contact_restart.sh MORAINE OUTDIR PYTHON
set -u
moraine=$1 out=$2 python=$3
here=$(cd "$(dirname "$0")" && pwd)
deck=$here/contact_restart.lua
rm -rf "$out"; mkdir -p "$out"
a=$("$moraine" "$deck" -q -o "$out/straight" --set save="$out/mid.h5" | grep '^state') ||
  { echo "FAIL: the straight run failed"; exit 1; }
# the save falls where contacts are held (doc/checkpoint-format.md, /grid/bodies_held)
held=$("$python" -c 'import sys, h5py; print(int(h5py.File(sys.argv[1], "r")["/grid"].attrs["bodies_held_count"]))' \
  "$out/mid.h5") || { echo "FAIL: /grid bodies_held_count not readable"; exit 1; }
[ "$held" -gt 0 ] || { echo "FAIL: the checkpoint holds no node where the bodies' contact held"; exit 1; }
b=$("$moraine" "$deck" -q -o "$out/restart" --set save="$out/mid2.h5" --restart "$out/mid.h5" | grep '^state') ||
  { echo "FAIL: the restart failed"; exit 1; }
[ "$a" = "$b" ] || { echo "FAIL: the restarted run differs:"; echo "  $a"; echo "  $b"; exit 1; }
echo "ok: --restart between the runs ends on the same state ($held nodes held at the save): $a"
