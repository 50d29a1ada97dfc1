"""moraine: the figures of the validation report (scripts/validation/report.py).

Each plotter reads the files a case's run wrote in OUT/<key>/ (engine
diagnostics CSVs, the decks' own CSVs) or its RESULT records, and draws
doc/figures/<key>.png. draw() returns the file name, or None (with a warning)
when the run left nothing to draw.
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PNG_META = {"Software": None}  # no version stamp: the same run gives the same file


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]} if rows else {}


def finish(fig, ax, path, title, xlabel, ylabel, legend=True):
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    if legend:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100, metadata=PNG_META)
    plt.close(fig)


def settling_energy(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(7, 4))
    for d, label in (("0.1", "Cundall D = 0.1"), ("0", "no damping")):
        c = read_csv(os.path.join(run, f"settle_D{d}.csv"))
        ax.semilogy(c["time"][1:], np.maximum(c["E_kinetic"][1:], 1e-12), label=label)
    finish(fig, ax, path, "Settling of an elastic column, FLIP (000 Fig. 13)", "t (s)", "E_k (J/m)")


def axial_bar(case, run, records, runs, path):
    c = read_csv(os.path.join(run, "bar.csv"))
    t, v = c["time"], c["momentum_x"] / c["mass"]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(t, v, label="moraine, v_cm")
    # first mode of the fixed-free bar: v_cm(t) = v_cm(0) cos(2 pi t / T), T = 4 L / c = 10 s
    tt = np.linspace(0, t[-1], 400)
    ax.plot(tt, 0.063662 * np.cos(2 * np.pi * tt / 10.0), "k--", lw=1, label="exact, T = 10 s")
    finish(fig, ax, path, "Vibrating bar: centre-of-mass velocity", "t (s)", "v_cm (m/s)")


def bouncing_cube_energy(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for f in sorted(glob.glob(os.path.join(run, "cube_*.csv"))):
        c = read_csv(f)
        ax.plot(c["time"], c["E_total"] / 1e3, label=os.path.basename(f)[5:-4])
    finish(fig, ax, path, "Bouncing cube (000 §4.1): total energy, USF, a_tau = 0.05", "t (s)", "E_total (kJ)")


def bouncing_cube_updates(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    styles = {"0.05": "-", "0.025": "--"}
    for i, update in enumerate(("USF", "USL", "MUSL", "USAVG")):
        for a_tau, ls in styles.items():
            f = os.path.join(run, f"upd_{update}_FLIP_{a_tau}.csv")
            if os.path.isfile(f):
                c = read_csv(f)
                ax.plot(c["time"], 100 * (c["E_total"] / c["E_total"][0] - 1), ls, color=f"C{i}",
                        label=f"{update}, a_tau = {a_tau}")
    finish(fig, ax, path, "Bouncing cube (000 §4.1), FLIP: total energy under each stress update", "t (s)",
           "E_total / E_ref - 1 (%)")


def rotating_cube_L(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(7, 4))
    for s in ("APIC", "AFLIP", "TFLIP"):
        f = os.path.join(run, f"cube_{s}.csv")
        if os.path.isfile(f):
            c = read_csv(f)
            ax.plot(c["time"], c["L_centroid"] / c["L_centroid"][0], label=s)
    finish(fig, ax, path, "Rotating cube (000 §4.2): angular momentum about the centroid", "t (s)", "L / L0")


def rotating_cube_scaling(case, run, records, runs, path):
    value = {r["id"].rsplit(".", 1)[1]: r["value"] for r in records}
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    labels = {"base": "a_tau = 0.05, omega", "dt2": "a_tau = 0.025, omega", "spin5": "a_tau = 0.05, 5 omega",
              "spin10": "a_tau = 0.05, 10 omega"}
    for ax, names in ((a, ("base", "dt2")), (b, ("base", "spin5", "spin10"))):
        for n in names:
            f = os.path.join(run, f"scaling_{n}.csv")
            if os.path.isfile(f):
                c = read_csv(f)
                ax.plot(c["time"], 100 * (1 - c["L_centroid"] / c["L_centroid"][0]), label=labels[n])
    b.set_yscale("log")
    a.set_title(f"time step: rate ratio {value.get('dt_ratio', float('nan')):.3f} (000: 0.5)", fontsize=10)
    a.set_xlabel("t (s)")
    a.set_ylabel("1 - L / L0 (%)")
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8)
    finish(fig, b, path, f"spin: ratios {value.get('spin5_ratio', float('nan')):.1f} (000: 24), "
           f"{value.get('spin10_ratio', float('nan')):.0f} (000: 95)", "t (s)", "1 - L / L0 (%)")


def bouncing_disk(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for s in ("PIC", "FLIP", "APIC"):
        f = os.path.join(run, f"disk_{s}.csv")
        if os.path.isfile(f):
            c = read_csv(f)
            ax.plot(c["time"], c["E_total"] / c["E_total"][0], label=s)
    finish(fig, ax, path, "Bouncing disk (000 App. B.1, Fig. 24): total energy, USL", "t (s)", "E_tot / E0")


def spinning_disk_apic(case, run, records, runs, path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, s in enumerate(("PIC", "FLIP", "APIC")):  # 000 Fig. 25: a_tau = 0.2
        for h, ls in (("0.0625", "-"), ("0.03125", "--")):
            f = os.path.join(run, f"disk_{s}_{h}_0.2.csv")
            if os.path.isfile(f):
                c = read_csv(f)
                a.plot(c["time"], c["L_centroid"] / c["L_centroid"][0], ls, color=f"C{i}", label=f"{s}, l_cell {h}")
    a.set_title("a_tau = 0.2 (000 Fig. 25)", fontsize=10)
    a.set_xlabel("t (s)")
    a.set_ylabel("L / L0")
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8)
    for i, a_tau in enumerate(("0.2", "0.1", "0.05", "0.01")):  # 000 Fig. 26: FLIP against dt and l_cell
        for h, ls in (("0.0625", "-"), ("0.03125", "--")):
            f = os.path.join(run, f"disk_FLIP_{h}_{a_tau}.csv")
            if os.path.isfile(f):
                c = read_csv(f)
                b.plot(c["time"], c["L_centroid"] / c["L_centroid"][0], ls, color=f"C{i}",
                       label=f"a_tau {a_tau}, l_cell {h}")
    finish(fig, b, path, "FLIP against a_tau and l_cell (000 Fig. 26)", "t (s)", "L / L0")


def pic_wmpm_collapse(case, run, records, runs, path):
    drop = next(r["value"] for r in records if r["id"].endswith(".drop"))
    spread = next(r["value"] for r in records if r["id"].endswith(".spread"))
    c = read_csv(os.path.join(run, "pic_wmpm.csv"))
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    for dt in sorted(set(c["dt"]), reverse=True):
        m = c["dt"] == dt
        a.plot(c["t_dt"][m], c["W_MPM"][m] / drop, "o-", ms=3, label=f"dt = {dt:.3g} s")
        b.plot(c["t"][m], c["W_MPM"][m] / drop, "o-", ms=3, label=f"dt = {dt:.3g} s")
    a.set_xlabel("t dt (s^2)")
    a.set_ylabel("W_MPM / |dE_p^stable|")
    a.set_title(f"against t dt: curves within {spread:.1f} % of |dE_p^stable|", fontsize=10)
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8)
    finish(fig, b, path, "against t: the same runs", "t (s)", "W_MPM / |dE_p^stable|")


def strip_footing(case, run, records, runs, path):
    c = read_csv(os.path.join(run, "footing.csv"))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(1e3 * c["settlement_m"], c["pressure_over_qu"], label="moraine, TPIC + WLS")
    ax.axhline(1.0, color="k", ls="--", lw=1, label="Prandtl (2 + pi) c")
    finish(fig, ax, path, "Strip footing (002 §5.2): load-settlement", "settlement (mm)", "q / q_u")


def prandtl_footing(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for tag, label in (("smooth_k3", "smooth, h = B/7"), ("smooth_k5", "smooth, h = B/11"),
                       ("smooth_k10", "smooth, h = B/21"), ("rough_k5", "rough, h = B/11"),
                       ("rough_k10", "rough, h = B/21"), ("mc_k5", "Mohr-Coulomb phi = 0, h = B/11"),
                       ("fbar_k3", "fbar, h = B/7"), ("fbar_k5", "fbar, h = B/11"), ("fbar_k10", "fbar, h = B/21"),
                       ("fbar_k5_nu0", "fbar, h = B/11, nu = 0"), ("fbar_k5_nu0.45", "fbar, h = B/11, nu = 0.45")):
        f = os.path.join(run, tag + ".csv")
        if os.path.isfile(f):
            c = read_csv(f)
            # scheme volumetric = "fbar" dashed
            ax.plot(c["settlement_over_B"][:-1], c["q_over_c"][:-1], "--" if tag.startswith("fbar") else "-",
                    label=label)
    ax.axhline(2 + np.pi, color="k", ls="--", lw=1, label="Prandtl 2 + pi")
    finish(fig, ax, path, "Strip footing through a wall: load-settlement", "settlement / B", "q / c")


def channel_convergence(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    by_transfer = {}
    for r in records:  # ids "<case>.<transfer>.E_N<cells>"; a transfer may contain a dot (FLIP0.99)
        head, last = r["id"].rsplit(".", 1)
        if last.startswith("E_N") and "." in head:
            by_transfer.setdefault(head.split(".", 1)[1], []).append((int(last[3:]), r["value"]))
    for transfer, pts in by_transfer.items():
        pts.sort()
        n = np.array([p[0] for p in pts], float)
        e = np.array([p[1] for p in pts])
        ax.loglog(n, e, "o-", label=transfer)
    n = np.array([8, 128], float)
    e0 = min(p[1] for pts in by_transfer.values() for p in pts[:1])
    ax.loglog(n, e0 * (n / 8) ** -2, "k--", lw=1, label="order 2")
    ax.loglog(n, e0 * (n / 8) ** -1, "k:", lw=1, label="order 1")
    finish(fig, ax, path, f"{case['name']}: error against the series", "cells across the channel N", "E(h)")


def dam_break(case, run, records, runs, path):
    front = read_csv(os.path.join(run, "front.csv"))
    mm = read_csv(os.path.join(run, "martin_moyce.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(front["T"], front["Z"], label="moraine, APIC + WLS")
    ax.plot(mm["T"], mm["Z_martin_moyce"], "ks", label="Martin & Moyce (1952)")
    finish(fig, ax, path, "Dam break (002 §5.4): surge front", "T = t sqrt(2 g / a)", "Z = front / a")


def sand_column(case, run, records, runs, path):
    c = read_csv(os.path.join(run, "front.csv"))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(c["t_over_tc"], c["front_m"], label="front")
    finish(fig, ax, path, "Sand column (002 §5.5): front position", "t / t_c", "x_front (m)")


def lube(case, run, records, runs, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    a = np.linspace(0.3, 1.8, 50)
    ax.plot(a, 1.2 * a, "k-", label="Lube et al.: 1.2 a")
    a2 = np.linspace(2.8, 3.4, 20)
    ax.plot(a2, 1.9 * a2 ** (2 / 3), "k--", label="Lube et al.: 1.9 a^(2/3)")
    for band in (0.8, 1.2):
        ax.plot(a, band * 1.2 * a, "k-", lw=0.5, alpha=0.4)
        ax.plot(a2, band * 1.9 * a2 ** (2 / 3), "k--", lw=0.5, alpha=0.4)
    pts = [(r["aspect_ratio"], r["value"]) for r in records if "aspect_ratio" in r]
    if pts:
        ax.plot(*zip(*pts), "o", ms=8, label="moraine, FLIP")
    finish(fig, ax, path, "Granular column collapse: final runout vs Lube et al. (2005), with their 20 %",
           "a = H_i / L_i", "L~ = (L_f - L_i) / L_i")
    collapse_picture(run, os.path.join(os.path.dirname(path), "column_collapse.png"))


def collapse_s2(case, run, records, runs, path):
    c = read_csv(os.path.join(run, "collapse_s2.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.2))
    cm = 100 * c["l_cell"]
    ax.plot(cm, c["L_x"], "o-", label="moraine, L_x (000, Eq. 70)")
    ax.plot(cm, c["max_x"], "s--", ms=4, label="moraine, furthest particle")
    coarse = c["L_x"][np.argmax(cm)]
    ax.axhline(1.07 * coarse, color="k", lw=0.8, ls=":", label="000: about +7 % below 10 cm")
    ax.invert_xaxis()
    finish(fig, ax, path, "Series S2 (000 Table 4): AR 1, FLIP, N_mppc 4", "l_cell (cm)", "final width (m)")


def collapse_s3(case, run, records, runs, path):
    c = read_csv(os.path.join(run, "collapse_s3.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.2))
    n = c["N_mppc"]
    for key, label in (("L_x", "standard"), ("L_x_split", "splitting"), ("L_x_cpdi", "CPDI")):
        keep = c[key] > 0
        if keep.any():
            ax.plot(n[keep], c[key][keep], "o-", label=label)
    ax.plot([n[0], n[-1]], [c["L_x"][0], 1.25 * c["L_x"][0]], "k:", lw=0.8, label="000: +25 % from 1 to 49")
    ax.set_xscale("log")
    finish(fig, ax, path, "Series S3 (000 Table 5): AR 1, FLIP, l_cell 10 cm", "N_mppc", "final L_x (m)")


def collapse_picture(run, path, ratio="2.4"):
    """the picture of the README: particles of the AR 2.4 FLIP collapse at
    three times, coloured by speed (read back with VTK's own reader)"""
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests", "python"))
    from vtk_read import read_pvd, read_vtp
    pvd = os.path.join(run, f"AR{ratio}_FLIP_collapse.pvd")
    series = read_pvd(pvd)
    picks = [series[0], series[len(series) // 6], series[-1]]
    fig, axes = plt.subplots(len(picks), 1, figsize=(6.2, 6.4), sharex=True, layout="constrained")
    vmax = 0
    data = []
    for t, f in picks:
        pts, arrays = read_vtp(f)
        speed = np.linalg.norm(arrays["velocity"], axis=1)
        vmax = max(vmax, speed.max())
        data.append((t, pts, speed))
    xmax = max(pts[:, 0].max() for _, pts, _ in data) + 0.2
    for ax, (t, pts, speed) in zip(axes, data):
        sc = ax.scatter(pts[:, 0], pts[:, 1], c=speed, s=2.5, cmap="viridis", vmin=0, vmax=vmax, lw=0)
        ax.set_aspect("equal")
        ax.set_xlim(0, xmax)
        ax.set_ylim(0, 2.6)
        ax.set_title(f"t = {t:.2f} s", fontsize=9)
        ax.set_ylabel("y (m)")
    axes[-1].set_xlabel("x (m)")
    fig.colorbar(sc, ax=axes, label="speed (m/s)", shrink=0.7)
    fig.suptitle("Granular column collapse, aspect ratio 2.4, FLIP (examples/column_collapse)", fontsize=10)
    fig.savefig(path, dpi=100, metadata=PNG_META)
    plt.close(fig)


PLOTTERS = {f.__name__: f for f in (settling_energy, axial_bar, bouncing_cube_energy, bouncing_cube_updates,
                                    rotating_cube_L, rotating_cube_scaling, bouncing_disk, spinning_disk_apic,
                                    pic_wmpm_collapse, strip_footing, prandtl_footing, channel_convergence, dam_break,
                                    sand_column, lube, collapse_s2, collapse_s3)}


def draw(name, case, out, records, runs, figures):
    if name not in PLOTTERS:
        raise SystemExit(f"case {case['key']}: no plotter '{name}' in {__file__}")
    path = os.path.join(figures, case["key"] + ".png")
    try:
        PLOTTERS[name](case, os.path.join(out, case["key"]), records, runs, path)
    except (OSError, KeyError, ValueError, IndexError, ImportError) as e:
        print(f"warning: no figure for {case['key']}: {type(e).__name__}: {e}", file=sys.stderr)
        return None
    return os.path.basename(path)
