"""The rolling disk example's picture: the centre's distance down the plane
against time with the closed forms, and the disks at the end coloured by
speed (a rolling disk is at rest at its contact point and fastest at its top).

    /usr/bin/python3 examples/rolling_disk/plot.py out/rolling [picture.png]
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: (np.array([float(r[k]) for r in rows]) if k != "motion" else [r[k] for r in rows]) for k in rows[0]}


def tag(mu):
    return f"{mu:g}".replace(".", "p")


def main(outdir, png):
    summary = read(os.path.join(outdir, "summary.csv"))
    n = len(summary["mu"])
    fig, axes = plt.subplots(1, 1 + n, figsize=(5 + 4.2 * n, 4.2))
    a = axes[0]
    for k, mu in enumerate(summary["mu"]):
        s = read(os.path.join(outdir, f"disk_mu{tag(mu)}.csv"))
        label = f"mu {mu:g} ({summary['motion'][k]}): a {summary['deviation_percent'][k]:+.1f} % off"
        line, = a.plot(s["time"], s["s"], "o", ms=3, label=label)
        a.plot(s["time"], s["s_closed_form"] + s["s"][0] - s["s_closed_form"][0], "-", color=line.get_color(), lw=1)
        p = read(os.path.join(outdir, f"disk_mu{tag(mu)}_final.csv"))
        b = axes[1 + k]
        sc = b.scatter(p["x"], p["y"], c=p["speed"], s=3, cmap="viridis")
        fig.colorbar(sc, ax=b, label="speed (m/s)")
        b.set_aspect("equal")
        b.set_xlabel("x (m)"), b.set_ylabel("y (m)")
        b.set_title(f"mu {mu:g}, at the end")
    a.set_xlabel("t (s)"), a.set_ylabel("centre's distance down the plane (m)")
    a.set_title("points: moraine; lines: the closed forms")
    a.legend(fontsize=8)
    a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    print(f"wrote {png}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else os.path.join(sys.argv[1], "rolling_disk.png"))
