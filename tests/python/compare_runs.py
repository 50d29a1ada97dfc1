#!/usr/bin/python3
"""moraine: two runs of the same problem wrote the same particle states.

usage: compare_runs.py DIR_A DIR_B SERIES

The .pvd SERIES of both directories, read with VTK's own reader, lists the
same times, and every snapshot holds the same points and the same arrays,
value for value (bit for bit, NaN equal to NaN): what the C API's
examples/c_api/drop.c must give against the deck it reproduces.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtk_read import read_pvd, read_vtp  # noqa: E402


def same_bits(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def main(a_dir, b_dir, series):
    a, b = read_pvd(os.path.join(a_dir, series + ".pvd")), read_pvd(os.path.join(b_dir, series + ".pvd"))
    fails = []
    if [t for t, _ in a] != [t for t, _ in b]:
        fails.append(f"the .pvd times differ: {[t for t, _ in a]} and {[t for t, _ in b]}")
    for (t, pa), (_, pb) in zip(a, b):
        xa, arrays_a = read_vtp(pa)
        xb, arrays_b = read_vtp(pb)
        if not same_bits(xa, xb):
            fails.append(f"t = {t}: the points differ")
        if sorted(arrays_a) != sorted(arrays_b):
            fails.append(f"t = {t}: arrays {sorted(arrays_a)} and {sorted(arrays_b)}")
        fails += [f"t = {t}: '{n}' differs" for n in sorted(arrays_a) if n in arrays_b and not same_bits(arrays_a[n], arrays_b[n])]
    for f in fails:
        print("FAIL:", f)
    print(f"{len(a)} snapshots of {read_vtp(a[-1][1])[0].shape[0]} particles compared")
    print(f"{0 if fails else 1} passed, {1 if fails else 0} failed")
    return 1 if fails else 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
