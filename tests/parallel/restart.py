#!/usr/bin/env python3
"""A checkpoint written on 3 processes loads on 1 and on 2 and continues
as the straight run does.

The straight run: the case on one process for 2 x HALF steps. The split
runs: the case on 3 processes for HALF steps (its final sim:save is the
checkpoint, gathered on process 0), then that file loaded on 1 and on 2
processes and run HALF steps more. Each final state is compared with the
straight run's particle by particle (ids, every field) and in the energy
books of the file (the clock, the works of friction and damping, the
reference of the energy balance), to 1e-12 as in equivalence.py.
Usage: restart.py MORAINE DECK WORKDIR CASE HALF
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import equivalence as eq  # noqa: E402


def run(moraine, deck, out, case, steps, np_, name, load=""):
    cmd = eq.mpirun(np_) + [moraine, "-q", "--overwrite", "-o", out, "--set", f"case={case}", "--set",
                            f"steps={steps}", "--set", f"name={name}", "--set", f"load={load}", deck]
    r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"), timeout=900)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return os.path.join(out, name + ".h5")


def books(path):
    with h5py.File(path, "r") as f:
        a = f["simulation"].attrs
        return {k: float(a[k]) for k in ("time", "step", "work_friction", "work_damping", "energy_ref") if k in a}


def main():
    moraine, deck, workdir, case, half = sys.argv[1:6]
    half = int(half)
    os.makedirs(workdir, exist_ok=True)
    straight = run(moraine, deck, os.path.join(workdir, "straight"), case, 2 * half, 1, "straight")
    mid = run(moraine, deck, os.path.join(workdir, "mid"), case, half, 3, "mid")
    ref = books(straight)
    if len(ref) < 5:
        sys.exit(f"FAIL: the checkpoint's /simulation lacks some of the books: {sorted(ref)}")
    for np_ in (1, 2):
        end = run(moraine, deck, os.path.join(workdir, f"on{np_}"), case, half, np_, f"on{np_}", load=mid)
        label = f"{case}: saved on 3 processes, continued on {np_}"
        eq.compare_states(straight, end, label)
        got = books(end)
        scale = max(abs(ref["energy_ref"]), 1.0)
        for k, v in ref.items():
            dev = abs(got[k] - v) / (scale if k.startswith(("work", "energy")) else max(abs(v), 1e-300))
            if dev > eq.TOL:
                sys.exit(f"FAIL {label}: {k} = {got[k]!r}, the straight run has {v!r}")
        print(f"{label}: clock and energy books as the straight run's (t = {got['time']:.6g} s, step {got['step']:.0f})")
    print("PASS")


if __name__ == "__main__":
    main()
