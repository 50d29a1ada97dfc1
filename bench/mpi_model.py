#!/usr/bin/env python3
"""Medians and ratios of bench/mpi.sh's runs, and a weak-scaling model of
the slab decomposition built from the measured costs.

Reads the lines bench/mpi_scaling.lua printed (and, if present, the line
`latency=S bandwidth=B/S` of bench/mpi_pingpong.py). For each problem:
the median particle-steps/s of 1 process x 1 thread, 1 x 2 and 2 x 1, and
the ratios 2x1 / 1x1 and 2x1 / 1x2.

Weak-scaling model (each process keeps the particles one process of the
2-process run had, n = N / 2, and its slab's cross-section: the domain
grows along the cut axis). Per step, with no overlap of computing and
communicating:
  t_compute = n / R1            R1: the 1 x 1 rate (particle-steps/s)
  t_halo    = 2 cuts x (k alpha + H / beta)
                                H: bytes process 0 sent per step across its
                                one cut in the 2-process run (measured); k:
                                exchanges per step and cut (2: mass and
                                momentum, then force; 3 with friction faces)
  t_reduce  = C alpha ceil(log2 P)
                                C = 14 agreements and sums of a few numbers
                                per step (halo sums, migration, watchdog,
                                hooks, the time step), latency-bound trees
  t_alltoall= 2 alpha (P - 1)   the migration's all-to-all of counts and of
                                particles, one message to and from every process
  t_move    = M / beta          M: bytes of particles sent per step (measured)
  efficiency(P) = t_compute / (t_compute + t_halo + t_reduce + t_alltoall + t_move)
alpha and beta: this machine's (measured by bench/mpi_pingpong.py, shared
memory) and two interconnects assumed: InfiniBand HDR (1 us, 24 GB/s) and
10 Gb Ethernet (20 us, 1.2 GB/s).
A second shape, a 3D cube grown in every direction, is bounded by the slabs
themselves: P slabs of at least 4 cells across a cube of c (P / 2)^(1/3)
cells (c: the 2-process cube's cells along the cut axis) exist only while
c (P / 2)^(1/3) >= 4 P; the largest such P is printed.
"""
import math
import re
import statistics
import sys

ALPHA_REDUCE_COUNT = 14
NETWORKS = [("InfiniBand HDR (assumed)", 1e-6, 24e9), ("10 Gb Ethernet (assumed)", 20e-6, 1.2e9)]
CELLS_ALONG_CUT = {"c32": 36, "collapse3d": 44, "a160k": 104}
EXCHANGES = {"collapse3d": 3}


def parse(path):
    runs, net = [], None
    for line in open(path):
        m = re.search(r"latency=(\S+) bandwidth=(\S+)", line)
        if m:
            net = ("this machine (measured, shared memory)", float(m.group(1)), float(m.group(2)))
            continue
        f = dict(re.findall(r"(\w+)=(\S+)", line))
        if "rate" in f:
            runs.append({"problem": line.split()[0], "P": int(f["processes"]), "T": int(f["threads"]),
                         "rate": float(f["rate"]), "n": int(f["particles"]),
                         "halo": float(f["halo_bytes_per_step"]), "move": float(f["migrate_bytes_per_step"])})
    return runs, net


def model(prob, r11, n, halo, move, nets):
    k = EXCHANGES.get(prob, 2)
    t_c = (n / 2) / r11
    rows = []
    for name, alpha, beta in nets:
        eff = []
        for P in (64, 1000, 10000):
            t = t_c + 2 * (k * alpha + halo / beta) + ALPHA_REDUCE_COUNT * alpha * math.ceil(math.log2(P)) \
                + 2 * alpha * (P - 1) + move / beta
            eff.append(t_c / t)
        rows.append((name, eff))
    return t_c, rows


def main():
    runs, net = parse(sys.argv[1])
    nets = ([net] if net else []) + NETWORKS
    print("\nproblem      particles  1x1 (p-s/s)  1x2 (p-s/s)  2x1 (p-s/s)  2x1/1x1  2x1/1x2  halo B/step  moved B/step")
    for prob in dict.fromkeys(r["problem"] for r in runs):
        med = {}
        for P, T in ((1, 1), (1, 2), (2, 1)):
            rates = [r["rate"] for r in runs if r["problem"] == prob and r["P"] == P and r["T"] == T]
            med[(P, T)] = statistics.median(rates) if rates else float("nan")
        two = [r for r in runs if r["problem"] == prob and r["P"] == 2]
        n = two[0]["n"] if two else 0
        halo = statistics.median(r["halo"] for r in two) if two else 0.0
        move = statistics.median(r["move"] for r in two) if two else 0.0
        print(f"{prob:12s} {n:9d}  {med[(1, 1)]:11.4g}  {med[(1, 2)]:11.4g}  {med[(2, 1)]:11.4g}  "
              f"{med[(2, 1)] / med[(1, 1)]:7.3f}  {med[(2, 1)] / med[(1, 2)]:7.3f}  {halo:11.0f}  {move:12.0f}")
        t_c, rows = model(prob, med[(1, 1)], n, halo, move, nets)
        print(f"  weak scaling, {n // 2} particles per process (t_compute {t_c * 1e3:.3g} ms/step): efficiency at "
              "64 / 1,000 / 10,000 processes")
        for name, eff in rows:
            print(f"    {name:40s} {eff[0]:6.3f} {eff[1]:6.3f} {eff[2]:6.3f}")
        c = CELLS_ALONG_CUT.get(prob)
        if c and prob != "a160k":
            P = 2
            while c * ((P + 1) / 2) ** (1 / 3) >= 4 * (P + 1):
                P += 1
            print(f"  a cube grown in every direction keeps slabs of 4 cells up to {P} processes")


if __name__ == "__main__":
    main()
