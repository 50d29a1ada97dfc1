"""The front of a collapse, read from its VTK snapshots: where the runout of
000's Eq. 70 comes from.

    /usr/bin/python3 examples/column_collapse/front.py out/collapse/AR0.6_FLIP_collapse.pvd [--mu 0.3]

Reads every snapshot of the series through VTK's own reader (python3-vtk9;
the deck writes velocity, displacement, stress and id) and prints

- L~ against t~ (000, Eqs. 70-73) from the furthest particle and from the
  particle below which 99 % and 95 % of them lie, and the furthest
  particle's x;
- the furthest particle's history: where it started (position minus
  displacement), when it reached the floor (centre within half a cell), its
  speed there and its mean deceleration from there to rest in units of
  mu g, both from its motion (snapshot to snapshot), and the largest gap
  between its stored velocity and its motion;
- where it would have stopped had it decelerated at mu g from the floor on;
- the particles of the front cell when the furthest one reaches the floor:
  how fast their mean stored velocity slows (in mu g), and their stress when
  loaded, sigma_xx / sigma_yy, beside Mohr-Coulomb's active ratio K_a: what
  pushes a tail whose thickness falls towards its front;
- at the last snapshot, the share of the kinetic energy (of sum |v|^2: the
  particles' masses are equal) in the particles within half a cell of the
  floor, and the largest stored velocity into the floor among them: what a
  FLIP particle keeps of the floor's stop (doc/numerics.md, "What FLIP
  remembers of a face's stop").

Options: --cell (m, 0.1), --width (L_x^init, m, 1), --ar (default: from the
name AR<a>_...), --mu (0.3), --g (9.81), --phi (friction angle, deg, 33.75).
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def snapshots(pvd):
    """(time, path) of each data set of a .pvd collection, in time order"""
    root = ET.parse(pvd).getroot()
    base = os.path.dirname(pvd)
    sets = [(float(d.get("timestep")), os.path.join(base, d.get("file"))) for d in root.iter("DataSet")]
    return sorted(sets)


def read(path):
    """positions, stored velocities, initial positions and stresses, keyed by id"""
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    fields = data.GetPointData()
    x = vtk_to_numpy(data.GetPoints().GetData())[:, :2]
    v = vtk_to_numpy(fields.GetArray("velocity"))[:, :2]
    u = vtk_to_numpy(fields.GetArray("displacement"))[:, :2]
    sigma = vtk_to_numpy(fields.GetArray("stress"))[:, :2]  # xx, yy (tension positive)
    ids = vtk_to_numpy(fields.GetArray("id")).astype(np.int64)
    return {"x": x, "v": v, "x0": x - u, "sigma": sigma, "id": ids, "row": {int(i): k for k, i in enumerate(ids)}}


def runout(x_max, o):
    """L~ of a front at x_max: 000, Eqs. 70-72"""
    Lx = math.floor(x_max / o.cell + 1.0) * o.cell
    return (Lx - o.width) / o.width


def front_table(series, o, tscale):
    print(f"{'t (s)':>7} {'t~':>6} {'L~':>5} {'L~ 99%':>7} {'L~ 95%':>7} {'front (m)':>10}")
    step = max(1, len(series) // 20)
    for t, s in series[::step] + ([series[-1]] if (len(series) - 1) % step else []):
        xs = np.sort(s["x"][:, 0])
        n = len(xs)
        print(f"{t:7.2f} {t / tscale:6.2f} {runout(xs[-1], o):5.1f} {runout(xs[int(0.99 * n)], o):7.1f} "
              f"{runout(xs[int(0.95 * n)], o):7.1f} {xs[-1]:10.3f}")


def path_of(series, pid):
    """times, positions and stored velocities of one particle"""
    rows = [(t, s["x"][s["row"][pid]], s["v"][s["row"][pid]]) for t, s in series if pid in s["row"]]
    t = np.array([r[0] for r in rows])
    return t, np.array([r[1] for r in rows]), np.array([r[2] for r in rows])


def landing(series, o):
    """the furthest particle at the end: its id, path, motion along x and the
    snapshot at which its centre first lies within half a cell of the floor
    (None if it never does)"""
    last = series[-1][1]
    k = int(np.argmax(last["x"][:, 0]))
    pid = int(last["id"][k])
    t, x, v = path_of(series, pid)
    motion = np.gradient(x[:, 0], t)  # its speed along x from its positions
    down = np.nonzero(x[:, 1] < 0.5 * o.cell)[0]
    return pid, t, x, v, motion, (int(down[0]) if len(down) else None)


def rest_index(motion, i):
    """the first snapshot from i on at which a motion is below 0.02 m/s (the last if none)"""
    still = motion[i:] < 0.02
    return (i + int(np.argmax(still)) if np.any(still) else len(motion) - 1), bool(np.any(still))


def furthest_history(series, o, land):
    pid, t, x, v, motion, i = land
    last = series[-1][1]
    x0 = last["x0"][last["row"][pid]]
    print(f"\nfurthest particle (id {pid}): started at x = {x0[0]:.3f} m, y = {x0[1]:.3f} m; "
          f"ends at x = {x[-1, 0]:.3f} m")
    if i is None:
        print("  never within half a cell of the floor")
        return
    mug = o.mu * o.g
    print(f"  on the floor from t = {t[i]:.2f} s at x = {x[i, 0]:.3f} m, moving at {motion[i]:.2f} m/s")
    rest, stopped = rest_index(motion, i)
    if rest == i:
        print("  (at rest or at the last snapshot there: nothing more to measure)")
        return
    decel = (motion[i] - motion[rest]) / (t[rest] - t[i])
    gap = np.max(np.abs(v[i:, 0] - motion[i:]))
    print(f"  at rest (< 0.02 m/s) from t = {t[rest]:.2f} s" if stopped
          else f"  still moving at the end ({motion[-1]:.2f} m/s)")
    print(f"  mean deceleration on the floor {decel:.2f} m/s^2 = {decel / mug:.2f} mu g; "
          f"stored velocity off its motion by up to {gap:.2f} m/s")
    stop = x[i, 0] + motion[i] ** 2 / (2.0 * mug)
    print(f"  at mu g from there it would stop at x = {stop:.3f} m: L~ = {runout(stop, o):.1f} "
          f"(it reached L~ = {runout(x[-1, 0], o):.1f})")


def front_group(series, o, land):
    """The particles of the front cell when the furthest one lands: how their
    momentum slows (friction alone would slow it at mu g) and their stress
    when loaded, against Mohr-Coulomb's active ratio K_a: a thin layer whose
    thickness falls towards its front is pushed forward by the horizontal
    stress of the thicker part behind it (the K dh/dx term of a thin-layer
    model)."""
    pid, t, x, v, motion, i = land
    if i is None:
        return
    rest, _ = rest_index(motion, i)
    if rest == i:
        return
    s_land = series[int(np.searchsorted([ts for ts, _ in series], t[i]))][1]
    group = [int(q) for q, xq in zip(s_land["id"], s_land["x"][:, 0]) if xq > x[i, 0] - o.cell]
    mean_v, ratios = [], []
    for ts, s in series:
        if t[i] <= ts <= t[rest]:
            rows = [s["row"][q] for q in group]
            mean_v.append(np.mean(s["v"][rows, 0]))
            sig = s["sigma"][rows]
            loaded = sig[:, 1] < -100.0  # compressed, not at the tension cut-off
            ratios.extend(sig[loaded, 0] / sig[loaded, 1])
    decel = (mean_v[0] - mean_v[-1]) / (t[rest] - t[i])
    ka = (1.0 - math.sin(math.radians(o.phi))) / (1.0 + math.sin(math.radians(o.phi)))
    print(f"  the {len(group)} particles of its cell and ahead of it then: their mean stored velocity slows at "
          f"{decel / (o.mu * o.g):.2f} mu g to t = {t[rest]:.2f} s")
    if ratios:
        print(f"  their stress when loaded (sigma_yy < -100 Pa, {len(ratios)} samples): sigma_xx / sigma_yy median "
              f"{np.median(ratios):.2f} (Mohr-Coulomb's active K_a = {ka:.3f} at phi = {o.phi} deg)")


def floor_memory(series, o):
    last = series[-1][1]
    v2 = np.sum(last["v"] ** 2, axis=1)
    low = last["x"][:, 1] < 0.5 * o.cell
    share = np.sum(v2[low]) / np.sum(v2) if np.sum(v2) > 0 else 0.0
    into = -np.min(last["v"][low, 1]) if np.any(low) else 0.0
    print(f"\nat t = {series[-1][0]:.2f} s: {100 * share:.0f} % of the kinetic energy in the {int(np.sum(low))} "
          f"particles within half a cell of the floor; their largest velocity into it {max(into, 0.0):.2f} m/s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("pvd")
    ap.add_argument("--cell", type=float, default=0.1)
    ap.add_argument("--width", type=float, default=1.0)
    ap.add_argument("--ar", type=float, default=None)
    ap.add_argument("--mu", type=float, default=0.3)
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--phi", type=float, default=33.75)
    o = ap.parse_args()
    if o.ar is None:
        m = re.search(r"AR([0-9.]+)_", os.path.basename(o.pvd))
        if not m:
            sys.exit("front.py: give --ar (the name does not start with AR<a>_)")
        o.ar = float(m.group(1))
    series = [(t, read(p)) for t, p in snapshots(o.pvd)]
    if len(series) < 3:
        sys.exit(f"front.py: {o.pvd} holds {len(series)} snapshots; at least 3 are needed")
    front_table(series, o, math.sqrt(o.ar * o.width / o.g))
    land = landing(series, o)
    furthest_history(series, o, land)
    front_group(series, o, land)
    floor_memory(series, o)


if __name__ == "__main__":
    main()
