#!/usr/bin/python3
"""moraine: the checkpoint a failed run leaves is readable with h5py.

usage: check_failed_state.py FILE.h5 -- opens it and checks the particle
datasets agree in count and the clock is past the start. The state may be the
last good one (an inverted particle aborts its step) or hold the non-finite
values or the particle outside the grid that the run reported."""
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
    step = int(f["simulation"].attrs["step"])
    ok = ok and n > 0 and step > 0
print(f"{path}: {n} particles at step {step}, non-finite {bool(bad)}, outside the grid {bool(outside)}")
print("1 passed, 0 failed" if ok else "0 passed, 1 failed")
sys.exit(0 if ok else 1)
