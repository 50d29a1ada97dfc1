"""The gate example's picture: the runout L~ against t~ for each gate speed
(the dot where the gate clears the column), and the final deposits.

    /usr/bin/python3 examples/gate_collapse/plot.py out/gate [picture.png]
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
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def profile(x, y, width=0.025):
    """the highest particle in each bin of x (the deposit's surface)"""
    bins = np.floor(x / width).astype(int)
    top = {}
    for b, h in zip(bins, y):
        top[b] = max(top.get(b, 0.0), h)
    keys = sorted(top)
    return np.array([(k + 0.5) * width for k in keys]), np.array([top[k] for k in keys])


def tag(v):
    return f"{v:g}".replace(".", "p")


def main(outdir, png):
    summary = read(os.path.join(outdir, "summary.csv"))
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 3.8), gridspec_kw={"width_ratios": [1, 1.6]})
    for k, v in enumerate(summary["speed"]):
        s = read(os.path.join(outdir, f"gate_{tag(v)}.csv"))
        line, = a.plot(s["t_tilde"], s["L_tilde"], label=f"gate {v:g} m/s: L~ = {summary['L_tilde'][k]:.2f}")
        lift = summary["lift_time"][k]
        if lift <= s["time"][-1]:
            at = np.interp(lift, s["time"], s["L_tilde"])
            t_tilde = lift * s["t_tilde"][-1] / s["time"][-1]
            a.plot([t_tilde], [at], "o", color=line.get_color())
        p = read(os.path.join(outdir, f"gate_{tag(v)}_final.csv"))
        x, h = profile(p["x"], p["y"])
        b.plot(x, h, color=line.get_color(), label=f"{v:g} m/s")
    a.set_xlabel("t~ = t / sqrt(H / g)"), a.set_ylabel("L~ (000, Eq. 72)")
    a.legend(fontsize=8)
    a.grid(alpha=0.3)
    b.set_aspect("equal")
    b.set_xlabel("x (m)"), b.set_ylabel("y (m)")
    b.set_title("final surface: the highest particle per 2.5 cm of x (the gate stood at x = 0.5 m)")
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    print(f"wrote {png}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else os.path.join(sys.argv[1], "gate_collapse.png"))
