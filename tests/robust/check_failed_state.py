#!/usr/bin/python3
"""moraine: the checkpoint a failed run leaves is readable with h5py.

usage: check_failed_state.py FILE.h5 -- opens it, checks the particle datasets
agree in count and that at least one value is non-finite or a particle lies
outside the grid (the diagnosis the run reported)."""
import sys

import h5py
import numpy as np

path = sys.argv[1]
with h5py.File(path, "r") as f:
    n = int(f["particles"].attrs["count"])
    x = f["particles/x"][...]
    v = f["particles/v"][...]
    ok = x.shape == (n, 3) and v.shape == (n, 3) and f["particles/stress"].shape == (n, 6)
    origin, size = f["grid"].attrs["origin"], f["grid"].attrs["size"]
    dim = int(f["grid"].attrs["dim"])
    bad = (~np.isfinite(x)).any() or (~np.isfinite(v)).any()
    outside = ((x[:, :dim] < origin[:dim]) | (x[:, :dim] > origin[:dim] + size[:dim])).any()
    ok = ok and (bad or outside)
print(f"{path}: {n} particles, non-finite {bool(bad)}, outside the grid {bool(outside)}")
print("1 passed, 0 failed" if ok else "0 passed, 1 failed")
sys.exit(0 if ok else 1)
