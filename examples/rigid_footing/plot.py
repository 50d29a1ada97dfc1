"""The footing example's picture: the soil's deviatoric strain eps_D at the
end, with the footing, and the settlement over time (from diagnostics.h5).

    /usr/bin/python3 examples/rigid_footing/plot.py out/footing [picture.png]
"""
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402


def last_frame(outdir):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(sorted(glob.glob(os.path.join(outdir, "footing_*.vtp")))[-1])
    r.Update()
    out = r.GetOutput()
    return vtk_to_numpy(out.GetPoints().GetData()), vtk_to_numpy(out.GetPointData().GetArray("eps_D"))


def main(outdir, png):
    x, eps = last_frame(outdir)
    with h5py.File(os.path.join(outdir, "diagnostics.h5"), "r") as f:
        t, s = f["time"][()], f["settlement"][()]
        keep = np.isfinite(s)
        t, s = t[keep], s[keep]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 3.6), gridspec_kw={"width_ratios": [2, 1]})
    sc = a.scatter(x[:, 0], x[:, 1], c=eps, s=2, cmap="viridis")
    fig.colorbar(sc, ax=a, label="eps_D")
    a.add_patch(plt.Rectangle((2.5, 3.0 - s[-1]), 1.0, 0.5, color="0.4"))
    a.set_aspect("equal")
    a.set_xlim(0, 6), a.set_ylim(0, 4)
    a.set_xlabel("x (m)"), a.set_ylabel("y (m)")
    a.set_title("deviatoric strain at t = %.1f s" % t[-1])
    b.plot(t, 1e3 * s)
    b.set_xlabel("t (s)"), b.set_ylabel("settlement (mm)")
    b.set_title("footing settlement")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "footing.png")
