#!/usr/bin/env python3
"""Latency and bandwidth between two MPI processes on this machine
(mpi4py, Open MPI): half the round-trip time of a 1-byte message, and the
bytes per second of 8 MB messages. Run as `scripts/mpirun -np 2 python3
bench/mpi_pingpong.py`; process 0 prints `latency=SECONDS bandwidth=B/S`."""
import time

import numpy as np
from mpi4py import MPI

comm = MPI.COMM_WORLD
rank = comm.Get_rank()
peer = 1 - rank


def pingpong(nbytes, reps):
    buf = np.zeros(max(nbytes, 1), dtype=np.uint8)
    comm.Barrier()
    t0 = time.perf_counter()
    for _ in range(reps):
        if rank == 0:
            comm.Send(buf, dest=peer)
            comm.Recv(buf, source=peer)
        else:
            comm.Recv(buf, source=peer)
            comm.Send(buf, dest=peer)
    return (time.perf_counter() - t0) / (2 * reps)


pingpong(1, 100)  # warm-up
lat = min(pingpong(1, 2000) for _ in range(3))
big = 8 << 20
t = min(pingpong(big, 20) for _ in range(3))
if rank == 0:
    print(f"latency={lat:.4g} bandwidth={big / t:.4g}")
