#!/usr/bin/python3
"""moraine: read every .vtp of a run and its .pvd with the real VTK reader.

usage: check_run_vtk.py OUTDIR SERIES [SERIES ...]

For each series (a .pvd path relative to OUTDIR, without extension):
  - the .pvd lists files whose times increase, and every file it lists exists
    and is read by vtkXMLPolyDataReader with the expected number of points;
  - points are 3D (z = 0 for a 2D run) and the arrays moraine documents are there;
  - the last file's velocity, mass, stress and id equal the state the deck
    dumped with sim:field() (SERIES.state), to round-off (binary is exact).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtk_read import read_pvd, read_vtp  # noqa: E402

EXPECTED_ARRAYS = {"velocity": 3, "displacement": 3, "mass": 1, "volume": 1, "density": 1, "stress": 6,
                   "strain": 6, "pressure": 1, "von_mises": 1, "eps_D": 1, "material": 1, "id": 1}


def read_state(path):
    state = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts[0] == "count":
                state["count"] = int(parts[1])
            else:
                ncomp = int(parts[1])
                values = np.array([float(v) for v in parts[2:]])
                state[parts[0]] = values.reshape(-1, ncomp) if ncomp > 1 else values
    return state


def main():
    outdir, series = sys.argv[1], sys.argv[2:]
    passed = failed = 0

    def check(cond, what):
        nonlocal passed, failed
        if cond:
            passed += 1
        else:
            failed += 1
            print("FAIL:", what)

    for name in series:
        state = read_state(os.path.join(outdir, name + ".state"))
        entries = read_pvd(os.path.join(outdir, name + ".pvd"))
        check(len(entries) >= 3, f"{name}: {len(entries)} files in the .pvd")
        times = [t for t, _ in entries]
        check(all(b > a for a, b in zip(times, times[1:])), f"{name}: times increase {times}")
        listed = {os.path.basename(p) for _, p in entries}
        on_disk = {f for f in os.listdir(os.path.dirname(entries[0][1])) if f.startswith(os.path.basename(name) + "_")}
        check(listed == on_disk, f"{name}: .pvd lists {sorted(listed)}, directory has {sorted(on_disk)}")
        for _, path in entries:
            points, arrays = read_vtp(path)
            check(points.shape == (state["count"], 3), f"{path}: points {points.shape}")
            for arr, ncomp in EXPECTED_ARRAYS.items():
                got = arrays.get(arr)
                ok = got is not None and (got.shape[1] if got.ndim == 2 else 1) == ncomp
                check(ok, f"{path}: array {arr} with {ncomp} components")
        points, arrays = read_vtp(entries[-1][1])
        if "run2d" in name:
            check(np.all(points[:, 2] == 0.0), f"{name}: z = 0 in 2D")
        for field in ("velocity", "mass", "stress", "id"):
            check(np.array_equal(arrays[field], state[field]), f"{name}: last file's {field} equals the state")
    # reductions computed by the deck with sim:reduce, recomputed here from the last file
    red_path = os.path.join(outdir, "run2d.reductions")
    if os.path.exists(red_path):
        entries = read_pvd(os.path.join(outdir, "run2d.pvd"))
        points, arrays = read_vtp(entries[-1][1])
        arrays = dict(arrays, x=points[:, 0], y=points[:, 1])
        with open(red_path) as f:
            for line in f:
                op, field, subset, value = line.split()
                data = arrays[field]
                if subset.startswith("component"):
                    data = data[:, int(subset[len("component"):]) - 1]
                elif data.ndim == 2:
                    data = np.linalg.norm(data, axis=1)
                mask = np.ones(points.shape[0], dtype=bool)
                if subset == "upper":
                    mask = points[:, 1] >= 0.5
                elif subset == "left":
                    mask = points[:, 0] < 0.5
                data = data[mask]
                expected = {"max": np.max, "min": np.min, "sum": np.sum, "mean": np.mean,
                            "count": lambda a: float(a.size)}[op](data)
                check(abs(float(value) - expected) <= 1e-12 * max(1.0, abs(expected)),
                      f"reduce {op} {field} {subset}: Lua {value}, numpy {expected}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
