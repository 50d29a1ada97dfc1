"""The Prandtl footing example's picture: the load-settlement curve q/c
against settlement/B with Prandtl's 2 + pi, and the soil's deviatoric
strain eps_D at the end (Prandtl's mechanism) when the run wrote VTK.

    /usr/bin/python3 examples/prandtl_footing/plot.py out/prandtl [picture.png]
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def curve(outdir):
    with open(os.path.join(outdir, "footing.csv")) as f:
        rows = list(csv.DictReader(f))[:-1]  # the last step is shortened to end on time
    return (np.array([float(r["settlement_over_B"]) for r in rows]),
            np.array([float(r["q_over_c"]) for r in rows]))


def last_frame(outdir):
    files = sorted(glob.glob(os.path.join(outdir, "footing_*.vtp")))
    if not files:
        return None
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(files[-1])
    r.Update()
    out = r.GetOutput()
    return vtk_to_numpy(out.GetPoints().GetData()), vtk_to_numpy(out.GetPointData().GetArray("eps_D"))


def main(outdir, png):
    s, q = curve(outdir)
    frame = last_frame(outdir)
    fig, axes = plt.subplots(1, 2 if frame else 1, figsize=(11 if frame else 6, 4))
    a = axes[0] if frame else axes
    a.plot(s, q, label="moraine")
    a.axhline(2 + np.pi, color="k", ls="--", lw=1, label="Prandtl 2 + pi")
    a.set_xlabel("settlement / B"), a.set_ylabel("q / c")
    a.set_title("load-settlement")
    a.grid(True, alpha=0.3)
    a.legend()
    if frame:
        x, eps = frame
        b = axes[1]
        sc = b.scatter(x[:, 0], x[:, 1], c=eps, s=6, cmap="viridis", vmax=np.percentile(eps, 99))
        fig.colorbar(sc, ax=b, label="eps_D")
        b.plot([0, 0.5], [5, 5], "r", lw=4)
        b.set_aspect("equal")
        b.set_xlim(0, 1.6), b.set_ylim(4.3, 5.05)
        b.set_xlabel("x (m)"), b.set_ylabel("y (m)")
        b.set_title("deviatoric strain at the end (footing in red)")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "prandtl_footing.png")
