#!/usr/bin/python3
"""moraine: read the files left by `test_vtk DIR` with VTK's own reader.

    test_vtk DIR && /usr/bin/python3 tests/python/test_vtk_roundtrip.py DIR

The expected values mirror make_sample() in tests/unit/test_vtk.c."""

import json
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


def check_forms(d, exp):
    """the zlib, Float32 and time forms read back as the raw file, or as its
    values rounded to Float32"""
    check_file(os.path.join(d, "roundtrip_zlib.vtp"), exp, "zlib")
    check_file(os.path.join(d, "roundtrip_time.vtp"), exp, "zlib level 9 with a time")
    f32 = dict(exp)
    for k in ("points", "stress", "mass"):
        f32[k] = exp[k].astype(np.float32)
    for name in ("roundtrip_f32.vtp", "roundtrip_f32_zlib.vtp", "roundtrip_f32_ascii.vtp"):
        points, arrays = vtk_read.read_vtp(os.path.join(d, name))
        check(points.dtype == np.float32 and np.array_equal(points, f32["points"]), f"{name}: Float32 points")
        for k in ("stress", "mass"):
            a = arrays.get(k)
            check(a is not None and a.dtype == np.float32 and np.array_equal(a.reshape(f32[k].shape), f32[k]),
                  f"{name}: Float32 {k}")
        check(np.array_equal(arrays.get("id"), exp["id"]) and np.array_equal(arrays.get("material"), exp["material"]),
              f"{name}: integers kept")
    check(vtk_read.time_value(os.path.join(d, "roundtrip_time.vtp")) == 0.125, "TimeValue field data")
    check(vtk_read.time_value(os.path.join(d, "roundtrip_zlib.vtp")) is None, "no TimeValue unless asked")
    points, arrays = vtk_read.read_vtp(os.path.join(d, "roundtrip_empty_zlib.vtp"))
    check(points.shape == (0, 3) and all(a.shape[0] == 0 for a in arrays.values()), "empty zlib file")
    # several zlib blocks
    pr, ar = vtk_read.read_vtp(os.path.join(d, "big.vtp"))
    pz, az = vtk_read.read_vtp(os.path.join(d, "big_zlib.vtp"))
    check(pr.shape == (20000, 3) and np.array_equal(pr, pz) and np.array_equal(ar["stress"], az["stress"]),
          "a file of 15 zlib blocks reads back as the raw one")
    sr, sz = os.path.getsize(os.path.join(d, "big.vtp")), os.path.getsize(os.path.join(d, "big_zlib.vtp"))
    print(f"zlib: {sr} -> {sz} bytes ({sr / sz:.2f}x)")


def check_vtkhdf(d, exp):
    """the VTKHDF files hold what the raw .vtp holds, and their time"""
    points, arrays, t = vtk_read.read_vtkhdf(os.path.join(d, "roundtrip.vtkhdf"))
    check(np.array_equal(points, exp["points"]), "vtkhdf: point coordinates")
    check(sorted(arrays) == ["id", "mass", "material", "stress"], f"vtkhdf: array names {sorted(arrays)}")
    for k in ("stress", "mass", "id", "material"):
        a = arrays.get(k)
        check(a is not None and a.dtype == exp[k].dtype and np.array_equal(a, exp[k]), f"vtkhdf: {k}")
    check(t == 0.125, f"vtkhdf: TimeValue {t}")
    points, arrays, t = vtk_read.read_vtkhdf(os.path.join(d, "roundtrip_empty.vtkhdf"))
    check(points.shape == (0, 3) and t is None, "vtkhdf: an empty file, no time")
    # compressed (shuffle + deflate) and Float32
    points, arrays, t = vtk_read.read_vtkhdf(os.path.join(d, "roundtrip_zlib_f32.vtkhdf"))
    check(points.dtype == np.float32 and np.array_equal(points, exp["points"].astype(np.float32)),
          "vtkhdf zlib f32: Float32 points")
    for k in ("stress", "mass"):
        a = arrays.get(k)
        check(a is not None and a.dtype == np.float32 and np.array_equal(a, exp[k].astype(np.float32)),
              f"vtkhdf zlib f32: {k}")
    for k in ("id", "material"):
        check(np.array_equal(arrays.get(k), exp[k]) and arrays[k].dtype == exp[k].dtype, f"vtkhdf zlib f32: {k} kept")
    check(t == 0.25, f"vtkhdf zlib f32: TimeValue {t}")
    points, arrays, t = vtk_read.read_vtkhdf(os.path.join(d, "roundtrip_zlib_empty.vtkhdf"))
    check(points.shape == (0, 3) and all(a.shape[0] == 0 for a in arrays.values()), "vtkhdf zlib: an empty file")
    # ParaView's file series: JSON, names escaped, times exact
    with open(os.path.join(d, "roundtrip.vtkhdf.series")) as f:
        doc = json.load(f)
    check(doc == {"file-series-version": "1.0",
                  "files": [{"name": "roundtrip.vtkhdf", "time": 0.125},
                            {"name": "roundtrip_zlib_f32.vtkhdf", "time": 0.25},
                            {"name": 'odd "name"\\\t.vtkhdf', "time": 1e-300}]}, f"vtkhdf.series: {doc}")


def main():
    if len(sys.argv) != 2:
        print("usage: test_vtk_roundtrip.py DIR", file=sys.stderr)
        return 2
    d = sys.argv[1]
    exp = expected()
    try:
        check_file(os.path.join(d, "roundtrip.vtp"), exp, "binary")
        check_file(os.path.join(d, "roundtrip_ascii.vtp"), exp, "ascii")
        check_forms(d, exp)
        check_vtkhdf(d, exp)

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
