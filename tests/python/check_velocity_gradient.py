#!/usr/bin/python3
"""moraine: the velocity_gradient and vorticity particle fields read back from
the files of tests/decks/velocity_gradient.lua with VTK's own readers.

    moraine tests/decks/velocity_gradient.lua -o OUT && check_velocity_gradient.py OUT

For each case (2D and 3D rigid rotation at omega = 0.5 rad/s, 2D simple shear
at gdot = 0.2 1/s) and each form (binary, zlib + Float32, ascii, VTKHDF):
velocity_gradient has 9 components and equals the exact L; vorticity has 1
component in 2D and 3 in 3D and equals 2 omega (rotation) or -gdot (shear);
to 1e-12 (Float64) or Float32 rounding. The `all` form (no fields named)
holds neither field."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_read  # noqa: E402
from checklib import Checks  # noqa: E402

check = Checks("check_velocity_gradient")
OMEGA, GDOT = 0.5, 0.2
AXIS = np.array([1, 2, 2]) / 3.0


def skew(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


CASES = {
    "rotation2d": (skew([0, 0, OMEGA]), np.array([2 * OMEGA])),
    "rotation3d": (skew(OMEGA * AXIS), 2 * OMEGA * AXIS),
    "shear2d": (np.array([[0, GDOT, 0], [0, 0, 0], [0, 0, 0]]), np.array([-GDOT])),
}


def read(path):
    if path.endswith(".vtkhdf"):
        points, arrays, _ = vtk_read.read_vtkhdf(path)
    else:
        points, arrays = vtk_read.read_vtp(path)
    return points, arrays


def check_case(out, name, L, w):
    for form in ("bin", "zlib_f32", "ascii", "vtkhdf"):
        ext = ".vtkhdf" if form == "vtkhdf" else ".vtp"
        path = os.path.join(out, name, f"{form}_000000{ext}")
        label = f"{name}/{form}"
        _, arrays = read(path)
        tol = 1e-7 if "f32" in form else 1e-12
        grad = arrays.get("velocity_gradient")
        vort = arrays.get("vorticity")
        if not check(grad is not None and vort is not None, f"{label}: both fields present"):
            continue
        n = len(arrays["id"])
        check(grad.shape == (n, 9), f"{label}: velocity_gradient shape {grad.shape}, expected ({n}, 9)")
        err = np.max(np.abs(grad.astype(np.float64) - L.reshape(1, 9)))
        check(err <= tol, f"{label}: max |L - exact| = {err:.3g} > {tol:g}")
        shape = (n,) if len(w) == 1 else (n, 3)
        check(vort.shape == shape, f"{label}: vorticity shape {vort.shape}, expected {shape}")
        err_w = np.max(np.abs(vort.astype(np.float64).reshape(n, -1) - w.reshape(1, -1)))
        check(err_w <= tol, f"{label}: max |vorticity - exact| = {err_w:.3g} > {tol:g}")
        print(f"{label}: {n} particles, max error L {err:.2e}, vorticity {err_w:.2e} (1/s)")
    _, arrays = read(os.path.join(out, name, "all_000000.vtp"))
    check("stress" in arrays and "velocity_gradient" not in arrays and "vorticity" not in arrays,
          f"{name}/all: every built-in field but velocity_gradient and vorticity, got {sorted(arrays)}")


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    for name, (L, w) in CASES.items():
        check_case(argv[1], name, L, w)
    return check.report()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
