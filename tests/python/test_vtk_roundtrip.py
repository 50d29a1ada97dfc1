#!/usr/bin/python3
"""moraine: read the files left by `test_vtk DIR` with VTK's own reader.

    test_vtk DIR && /usr/bin/python3 tests/python/test_vtk_roundtrip.py DIR

The expected values mirror make_sample() in tests/unit/test_vtk.c."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_read  # noqa: E402
from checklib import Checks  # noqa: E402

NPTS = 37

check = Checks("test_vtk_roundtrip")


def expected():
    i = np.arange(NPTS, dtype=np.float64)
    points = np.stack([i * 0.25, -i * 0.125, 1.0 / (i + 1)], axis=1)
    stress = i[:, None] * 0.5 + np.arange(6, dtype=np.float64)[None, :]
    ids = np.arange(NPTS, dtype=np.int64) * 4294967296 + np.arange(NPTS, dtype=np.int64)
    return {
        "points": points,
        "stress": stress,
        "mass": 0.1 * i,
        "material": -np.arange(NPTS, dtype=np.int32),
        "id": ids,
    }


def check_file(path, exp, label):
    points, arrays = vtk_read.read_vtp(path)
    check(points.shape == (NPTS, 3), f"{label}: points shape {points.shape}")
    check(np.array_equal(points, exp["points"]), f"{label}: point coordinates")
    check(sorted(arrays) == ["id", "mass", "material", "stress"], f"{label}: array names {sorted(arrays)}")
    stress = arrays.get("stress")
    check(stress is not None and stress.shape == (NPTS, 6), f"{label}: stress has 6 components")
    check(stress is not None and stress.dtype == np.float64 and np.array_equal(stress, exp["stress"]),
          f"{label}: stress values")
    ids = arrays.get("id")
    check(ids is not None and ids.dtype == np.int64 and np.array_equal(ids, exp["id"]), f"{label}: Int64 ids")
    mat = arrays.get("material")
    check(mat is not None and mat.dtype == np.int32 and np.array_equal(mat, exp["material"]),
          f"{label}: Int32 material")
    mass = arrays.get("mass")
    check(mass is not None and mass.shape == (NPTS,) and np.array_equal(mass, exp["mass"]), f"{label}: mass")
    summary = vtk_read.summary(path)
    check(summary["points"] == NPTS and summary["arrays"] == {"stress": 6, "mass": 1, "material": 1, "id": 1},
          f"{label}: summary {summary}")


def main():
    if len(sys.argv) != 2:
        print("usage: test_vtk_roundtrip.py DIR", file=sys.stderr)
        return 2
    d = sys.argv[1]
    exp = expected()
    try:
        check_file(os.path.join(d, "roundtrip.vtp"), exp, "binary")
        check_file(os.path.join(d, "roundtrip_ascii.vtp"), exp, "ascii")

        points, arrays = vtk_read.read_vtp(os.path.join(d, "roundtrip_empty.vtp"))
        check(points.shape == (0, 3), f"empty: points shape {points.shape}")
        check(all(a.shape[0] == 0 for a in arrays.values()), "empty: arrays are empty")

        series = vtk_read.read_pvd(os.path.join(d, "roundtrip.pvd"))
        check([t for t, _ in series] == [0.0, 0.25, 1.0 / 3.0], f"pvd times {[t for t, _ in series]}")
        names = [os.path.basename(f) for _, f in series]
        check(names == ["roundtrip.vtp", "roundtrip_ascii.vtp", "roundtrip_empty.vtp"], f"pvd files {names}")
        check(all(os.path.isabs(f) and os.path.isfile(f) for _, f in series), "pvd files exist")

        check(not [f for f in os.listdir(d) if ".tmp." in f], "no temporary files left")
    except vtk_read.VtkReadError as e:
        check(False, str(e))
    return check.report()


if __name__ == "__main__":
    sys.exit(main())
