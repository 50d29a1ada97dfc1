#!/usr/bin/python3
"""moraine: every VTK file of a run equals the HDF5 checkpoint of the same state.

usage: check_outputs_roundtrip.py OUTDIR RUN [RUN ...]

OUTDIR/RUN holds what tests/decks/outputs_roundtrip.lua leaves: p.pvd with
p_NNNNNN.vtp, p_grid.pvd with p_grid_NNNNNN.vti, and ck_NNNNNN.h5 saved by a
hook at each snapshot. For every snapshot, read with VTK's own readers
(python3-vtk9) and the checkpoint with h5py:
  - the .pvd lists exactly the files on disk, and its times equal the model
    time stored in the checkpoint (/simulation attribute `time`), bit for bit;
  - points are 3D, equal /particles/x (z = 0 in 2D);
  - every point array of the .vtp is accounted for and equals the state:
    copies bit for bit, derived values (density, pressure, von Mises, eps_D)
    to round-off (RTOL), and the deck's registered fields (/particles/user);
  - every array of the .vti equals /grid/nodes over the domain nodes, and the
    image's origin, spacing and extent are the grid's;
  - the reductions the deck computed with sim:reduce (RUN/reductions.txt)
    equal numpy's over the last .vtp (all particles, a material, a region, a
    predicate).
Run with Debian's /usr/bin/python3 (python3-vtk9, python3-h5py, numpy)."""

import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_read  # noqa: E402
from checklib import Checks  # noqa: E402
from check_vti import read_image  # noqa: E402
from vtk.util import numpy_support  # noqa: E402

RTOL = 1e-13  # derived values: a few operations on doubles
check = Checks("check_outputs_roundtrip")


def close(a, b, rtol=RTOL):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if a.shape != b.shape:
        return False
    scale = max(1.0, float(np.max(np.abs(b)))) if b.size else 1.0
    return bool(np.all(np.abs(a - b) <= rtol * scale))


def sym_dev(s):
    d = s.copy()
    m = (s[:, 0] + s[:, 1] + s[:, 2]) / 3.0
    for k in range(3):
        d[:, k] -= m
    return d


def sym_ddot(s, t):
    return s[:, 0] * t[:, 0] + s[:, 1] * t[:, 1] + s[:, 2] * t[:, 2] + 2.0 * (
        s[:, 3] * t[:, 3] + s[:, 4] * t[:, 4] + s[:, 5] * t[:, 5])


def current_volume(p, dim):
    """vol0 det F (the checkpoint keeps no current volume); in 2D the in-plane block"""
    F = p["F"][...].reshape(-1, 3, 3)
    det = F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0] if dim == 2 else np.linalg.det(F)
    return p["vol0"][...] * det


def expected_particle_arrays(ck, dim):
    """name -> (values, exact) from the checkpoint, as the .vtp should hold them"""
    p = ck["particles"]
    x, x0 = p["x"][...], p["x0"][...]
    mass, vol = p["mass"][...], current_volume(p, dim)
    stress, strain = p["stress"][...], p["strain"][...]
    dev = sym_dev(stress)
    exp = {
        "velocity": (p["v"][...], True),
        "displacement": (x - x0, True),
        "mass": (mass, True),
        "volume": (vol, False),
        "density": (mass / vol, False),
        "stress": (stress, True),
        "strain": (strain, True),
        "pressure": (-(stress[:, 0] + stress[:, 1] + stress[:, 2]) / 3.0, False),
        "von_mises": (np.sqrt(1.5 * sym_ddot(dev, dev)), False),
        "eps_D": (np.sqrt(sym_ddot(sym_dev(strain), sym_dev(strain))), False),
        "elastic_energy": (p["e_elastic"][...], True),
        "deformation_gradient": (p["F"][...], True),
        "material": (p["material"][...], True),
        "id": (p["id"][...], True),
    }
    if "user" in p:
        for name in p["user"].attrs["names"].decode().split(","):
            exp[name] = (p["user"][name][...], True)
    return exp


def check_vtp(path, ck, dim, label):
    points, arrays = vtk_read.read_vtp(path)
    x = ck["particles"]["x"][...]
    check(points.shape == x.shape and np.array_equal(points, x), f"{label}: points equal /particles/x")
    if dim == 2:
        check(np.all(points[:, 2] == 0.0), f"{label}: z = 0 in 2D")
    exp = expected_particle_arrays(ck, dim)
    check(sorted(arrays) == sorted(exp), f"{label}: arrays {sorted(arrays)}, expected {sorted(exp)}")
    for name, (values, exact) in exp.items():
        got = arrays.get(name)
        if got is None:
            continue
        ok = np.array_equal(got, values) if exact else close(got, values)
        check(ok, f"{label}: array {name} equals the checkpoint" + ("" if exact else " to round-off"))
    return points, arrays


def check_vti(path, ck, dim, label):
    image = read_image(path)
    g = ck["grid"]
    ncell, origin, cell = g.attrs["ncell"], g.attrs["origin"], float(g.attrs["cell"])
    np_ = [int(ncell[d]) + 1 if d < dim else 1 for d in range(3)]
    check(list(image.GetDimensions()) == np_, f"{label}: dimensions {image.GetDimensions()}, expected {np_}")
    check(np.allclose(image.GetOrigin()[:dim], origin[:dim], rtol=0, atol=0), f"{label}: origin")
    check(image.GetSpacing()[0] == cell, f"{label}: spacing")
    nodes = g["nodes"]
    nnode = nodes.attrs["nnode"]
    pad = (int(nnode[0]) - np_[0]) // 2  # ghost layers on each side
    # the domain nodes of the full (ghost-padded) arrays, x fastest
    k, j, i = np.meshgrid(np.arange(np_[2]), np.arange(np_[1]), np.arange(np_[0]), indexing="ij")
    kk = k + pad if dim == 3 else k
    index = ((i + pad) + (j + pad) * int(nnode[0]) + kk * int(nnode[0]) * int(nnode[1])).ravel()
    pd = image.GetPointData()
    names = sorted(pd.GetArrayName(a) for a in range(pd.GetNumberOfArrays()))
    check(names == ["force", "mass", "velocity"], f"{label}: arrays {names}")
    for name in names:
        got = numpy_support.vtk_to_numpy(pd.GetArray(name))
        want = nodes[name][...][index]
        check(np.array_equal(got.reshape(want.shape), want), f"{label}: {name} equals /grid/nodes/{name}")


def check_reductions(path, points, arrays, label):
    data = dict(arrays, x=points[:, 0], y=points[:, 1], z=points[:, 2])
    n = 0
    with open(path) as f:
        for line in f:
            op, field, comp, subset, value = line.split()
            values = data[field]
            comp = int(comp)
            if values.ndim == 2:
                values = values[:, comp - 1] if comp else np.linalg.norm(values, axis=1)
            values = values.astype(np.float64)
            mask = np.ones(points.shape[0], dtype=bool)
            if subset.startswith("material"):
                mask = arrays["material"] == int(subset[len("material"):])
            elif subset == "upper":
                mask = points[:, 1] >= 0.5
            elif subset == "right":
                mask = points[:, 0] > 0.55
            check(subset == "all" or 0 < mask.sum() < mask.size, f"{label}: subset {subset} selects some particles")
            sel = values[mask]
            want = {"max": np.max, "min": np.min, "sum": np.sum, "mean": np.mean,
                    "count": lambda a: float(a.size)}[op](sel)
            check(abs(float(value) - want) <= 1e-12 * max(1.0, abs(want)),
                  f"{label}: reduce {op} {field} {subset}: Lua {value}, numpy {want!r}")
            n += 1
    check(n >= 15, f"{label}: {n} reductions")


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    outdir = argv[1]
    for run in argv[2:]:
        d = os.path.join(outdir, run)
        series = vtk_read.read_pvd(os.path.join(d, "p.pvd"))
        grid_series = vtk_read.read_pvd(os.path.join(d, "p_grid.pvd"))
        check(len(series) >= 3 and len(series) == len(grid_series), f"{run}: {len(series)} snapshots")
        on_disk = sorted(f for f in os.listdir(d) if f.endswith(".vtp") or f.endswith(".vti"))
        listed = sorted(os.path.basename(p) for _, p in series + grid_series)
        check(on_disk == listed, f"{run}: the .pvd files list {listed}, the directory has {on_disk}")
        last = None
        for k, ((t, vtp), (tg, vti)) in enumerate(zip(series, grid_series)):
            with h5py.File(os.path.join(d, f"ck_{k:06d}.h5"), "r") as ck:
                dim = int(ck["simulation"].attrs["dim"])
                t_model = float(ck["simulation"].attrs["time"])
                check(t == t_model and tg == t_model, f"{run}: snapshot {k}: .pvd times {t}, {tg}, model {t_model}")
                last = check_vtp(vtp, ck, dim, f"{run}/{os.path.basename(vtp)}")
                check_vti(vti, ck, dim, f"{run}/{os.path.basename(vti)}")
        check_reductions(os.path.join(d, "reductions.txt"), *last, run)
    return check.report()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
