"""The extrusion example's picture: the particles of each transfer's last VTK
snapshot coloured by speed (004 Fig. 4 colours them the same way).

    /usr/bin/python3 examples/extrusion/plot.py out/extrusion [picture.png]

Reads `<transfer>_*.vtp` through VTK's own reader (python3-vtk9), for the
transfers the run wrote (APIC, FLIP0_8, FLIP0_99, in that order).
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

TRANSFERS = ["APIC", "FLIP0_8", "FLIP0_99"]
V_MAX = 25.0  # mm/s: the colour scale's top, about twice the channel's mean speed


def last_snapshot(outdir, transfer):
    """positions (mm) and speeds (mm/s) of the transfer's last snapshot, or None"""
    files = sorted(glob.glob(os.path.join(outdir, transfer + "_*.vtp")))
    if not files:
        return None
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(files[-1])
    reader.Update()
    data = reader.GetOutput()
    x = vtk_to_numpy(data.GetPoints().GetData())
    v = vtk_to_numpy(data.GetPointData().GetArray("velocity"))
    return os.path.basename(files[-1]), 1e3 * x, 1e3 * np.linalg.norm(v, axis=1)


def main(outdir, png):
    runs = [(t, s) for t in TRANSFERS if (s := last_snapshot(outdir, t)) is not None]
    if not runs:
        sys.exit(f"plot.py: no <transfer>_*.vtp in {outdir}")
    fig, axes = plt.subplots(len(runs), 1, figsize=(8, 2.2 * len(runs)), squeeze=False, layout="constrained")
    for ax, (transfer, (name, x, speed)) in zip(axes[:, 0], runs):
        sc = ax.scatter(x[:, 0], x[:, 1], c=speed, s=0.5, vmin=0, vmax=V_MAX)
        ax.set_aspect("equal")
        ax.set_title(f"{transfer} ({name})", fontsize=10)
        ax.set_ylabel("y (mm)")
    axes[-1, 0].set_xlabel("x (mm)")
    fig.colorbar(sc, ax=list(axes[:, 0]), label="|v| (mm/s)", shrink=0.8)
    fig.savefig(png, dpi=90)
    print(f"wrote {png}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else os.path.join(sys.argv[1], "velocity.png"))
