#!/usr/bin/env python3
"""The same deck on 1, 2 and 3 processes gives the same run.

Runs tests/parallel/equivalence.lua (or the deck given) with the case given
on one process (no mpirun) and under `mpirun -np N` for each N, then
compares with the one-process run:
  - every column of the diagnostics CSV at every step, each relative to
    the largest magnitude that column takes in the one-process run (a
    momentum passing through zero has no relative error of its own), the
    energies and works (E_*, W_*) relative to the largest of them all:
    W_MPM is a difference of energies of that size, and carries their
    round-off;
  - every particle field of the final checkpoint (sim:save, particles in
    the order of their ids), the registered ones too, relative to the
    field's largest magnitude; its counters (next_id, particles split,
    added and deleted) exactly, its sources' books to the bound;
  - each wall's state in it (placement, a rigid body's velocities, the
    reaction, the impulse and works), relative to the largest magnitude
    of each, and the nodes in contact with it, exactly.
The bound is 1e-12 (doc/parallel.md: the sums over processes add the same
numbers in another order, so the runs agree to round-off, not bitwise).
Usage: equivalence.py MORAINE DECK WORKDIR CASE STEPS NP... [--rebalance N] [--transfer NAME] [--volumetric NAME]
       [--set KEY=VALUE]... (passed on to the deck)
"""
import csv
import os
import subprocess
import sys

import h5py
import numpy as np

TOL = 1e-12
FIELDS = ["x", "x0", "v", "mass", "vol0", "F", "affine", "stress", "strain", "e_elastic", "w_plastic", "state"]
WALL_STATE = ["velocity", "omega", "ref", "rot", "force", "moment", "impulse", "work", "work_friction", "body_work"]


def mpirun(np_):
    if np_ == 1:
        return []
    return ["mpirun", "--oversubscribe", "--allow-run-as-root", "-np", str(np_)]


def run(moraine, deck, workdir, case, steps, np_, rebalance, transfer=None, volumetric=None, sets=()):
    name = f"{case}_np{np_}" + (f"_rb{rebalance}" if rebalance else "")
    out = os.path.join(workdir, name)
    cmd = mpirun(np_) + [moraine, "-q", "--overwrite", "-o", out, "--set", f"case={case}", "--set", f"steps={steps}",
                         "--set", f"name={name}", "--set", f"rebalance={rebalance}", deck]
    if transfer:
        cmd[-1:-1] = ["--set", f"transfer={transfer}"]
    if volumetric:
        cmd[-1:-1] = ["--set", f"volumetric={volumetric}"]
    for s in sets:
        cmd[-1:-1] = ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return os.path.join(out, name + ".csv"), os.path.join(out, name + ".h5")


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    head = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    return head, data


def compare_csv(ref, other, label):
    head, a = read_csv(ref)
    head_b, b = read_csv(other)
    if head != head_b or a.shape != b.shape:
        sys.exit(f"FAIL {label}: the diagnostics differ in shape: {a.shape} vs {b.shape}")
    worst, where = 0.0, ""
    energy = [j for j, col in enumerate(head) if col[:2] in ("E_", "W_")]
    energy_scale = np.max(np.abs(a[:, energy]))
    for j, col in enumerate(head):
        # an energy or work, W_MPM above all (a small difference of large
        # energies), against the run's energy scale; the others their own
        scale = energy_scale if j in energy else np.max(np.abs(a[:, j]))
        if scale == 0.0:
            dev = np.max(np.abs(b[:, j]))
            if dev != 0.0:
                sys.exit(f"FAIL {label}: column {col} is 0 on one process and up to {dev:g} here")
            continue
        rel = np.max(np.abs(a[:, j] - b[:, j])) / scale
        if rel > worst:
            worst, where = rel, col
    print(f"{label}: diagnostics, {a.shape[0]} rows x {a.shape[1]} columns: largest deviation {worst:.3g} ({where})")
    if worst > TOL:
        sys.exit(f"FAIL {label}: diagnostics deviate by {worst:.3g} > {TOL:g} in {where}")
    return worst


def compare_books(fa, fb, label):
    """The counters of the checkpoints equal, the sources' books to TOL."""
    if fa["particles"].attrs["next_id"] != fb["particles"].attrs["next_id"]:
        sys.exit(f"FAIL {label}: next_id {fb['particles'].attrs['next_id']} is not "
                 f"{fa['particles'].attrs['next_id']}")
    for key in ("step", "split_count", "inflow_particles", "outflow_particles"):
        a, b = fa["simulation"].attrs[key], fb["simulation"].attrs[key]
        if a != b:
            sys.exit(f"FAIL {label}: {key} {b} is not {a}")
    for k in fa["sources"] if "sources" in fa else []:
        for key, a in fa["sources/" + k].attrs.items():
            b = fb["sources/" + k].attrs[key]
            if isinstance(a, float) and abs(a - b) > TOL * abs(a) or not isinstance(a, float) and a != b:
                sys.exit(f"FAIL {label}: source {k}'s {key} is {b}, not {a}")


def compare_states(ref, other, label):
    fa, fb = h5py.File(ref, "r"), h5py.File(other, "r")
    ida, idb = fa["particles/id"][:], fb["particles/id"][:]
    if not np.array_equal(ida, idb):
        sys.exit(f"FAIL {label}: the checkpoints hold different particles ({len(ida)} vs {len(idb)})")
    if not np.all(np.diff(ida) > 0):
        sys.exit(f"FAIL {label}: the checkpoint's particles are not in the order of their ids")
    compare_books(fa, fb, label)
    worst, where = 0.0, ""
    user = ["user/" + name for name in fa["particles/user"]] if "particles/user" in fa else []
    for name in FIELDS + user:
        if "particles/" + name not in fa:
            continue
        a, b = fa["particles/" + name][:], fb["particles/" + name][:]
        if a.size == 0:  # a model without history variables
            continue
        scale = np.max(np.abs(a))
        rel = np.max(np.abs(a - b)) / scale if scale > 0 else np.max(np.abs(b))
        if rel > worst:
            worst, where = rel, name
    print(f"{label}: {len(ida)} particles: largest deviation {worst:.3g} ({where})")
    if worst > TOL:
        sys.exit(f"FAIL {label}: particle states deviate by {worst:.3g} > {TOL:g} in {where}")
    compare_walls(fa, fb, label)
    return worst


def compare_walls(fa, fb, label):
    """Each wall's state in the checkpoints (placement, a body's velocities, the
    last reaction, the accumulated impulse and works) relative to its largest
    magnitude, and its contact nodes exactly."""
    if "walls" not in fa:
        return
    worst, where = 0.0, ""
    for key in fa["walls"]:
        ga, gb = fa["walls"][key], fb["walls"][key]
        wall = ga.attrs["name"].decode() if isinstance(ga.attrs["name"], bytes) else ga.attrs["name"]
        for name in WALL_STATE:
            if name not in ga.attrs:
                continue
            a, b = np.atleast_1d(ga.attrs[name]).astype(float), np.atleast_1d(gb.attrs[name]).astype(float)
            scale = np.max(np.abs(a))
            rel = np.max(np.abs(a - b)) / scale if scale > 0 else np.max(np.abs(b))
            if rel > worst:
                worst, where = rel, f"{wall}.{name}"
        if not np.array_equal(ga["contact"][:], gb["contact"][:]):
            sys.exit(f"FAIL {label}: wall {wall} is in contact at other nodes")
    print(f"{label}: {len(fa['walls'])} walls: largest deviation {worst:.3g} ({where}), the same contacts")
    if worst > TOL:
        sys.exit(f"FAIL {label}: wall states deviate by {worst:.3g} > {TOL:g} in {where}")


def main():
    args = sys.argv[1:]
    rebalance, transfer, volumetric, sets = 0, None, None, []
    while "--set" in args:
        i = args.index("--set")
        sets.append(args[i + 1])
        del args[i:i + 2]
    if "--transfer" in args:
        i = args.index("--transfer")
        transfer = args[i + 1]
        del args[i:i + 2]
    if "--volumetric" in args:
        i = args.index("--volumetric")
        volumetric = args[i + 1]
        del args[i:i + 2]
    if "--rebalance" in args:
        i = args.index("--rebalance")
        rebalance = int(args[i + 1])
        del args[i:i + 2]
    moraine, deck, workdir, case, steps = args[:5]
    nps = [int(n) for n in args[5:]]
    os.makedirs(workdir, exist_ok=True)
    ref_csv, ref_h5 = run(moraine, deck, workdir, case, steps, 1, 0, transfer, volumetric, sets)
    for np_ in nps:
        for rb in ([0, rebalance] if rebalance else [0]):
            if np_ == 1 and rb == 0:
                continue
            csv_, h5 = run(moraine, deck, workdir, case, steps, np_, rb, transfer, volumetric, sets)
            label = "".join(s + " " for s in sets) + (f"{transfer} " if transfer else "") + (f"{volumetric} " if volumetric else "") + f"{case} on {np_} process{'es' if np_ > 1 else ''}" + (f", re-cut every {rb} steps" if rb else "")
            compare_csv(ref_csv, csv_, label)
            compare_states(ref_h5, h5, label)
    print("PASS")


if __name__ == "__main__":
    main()
