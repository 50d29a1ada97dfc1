#!/usr/bin/env python3
"""The VTK series of a distributed run, read by ParaView's readers
(python3-vtk9): the .pvd lists every snapshot, and each snapshot holds every
particle exactly once (the ids 0 .. N-1, none twice) with the same values
as the one-process run's snapshot.
Usage: check_vtk.py DIR_ONE_PROCESS NAME_ONE DIR_N NAME_N"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def series(d, name):
    root = ET.parse(os.path.join(d, name + ".pvd")).getroot()
    return [os.path.join(d, ds.get("file")) for ds in root.iter("DataSet")]


def read(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    pd = out.GetPointData()
    ids = vtk_to_numpy(pd.GetArray("id"))
    order = np.argsort(ids)
    x = vtk_to_numpy(out.GetPoints().GetData())[order]
    v = vtk_to_numpy(pd.GetArray("velocity"))[order]
    return ids[order], x, v


def main():
    one = series(sys.argv[1], sys.argv[2])
    many = series(sys.argv[3], sys.argv[4])
    if len(one) != len(many) or len(one) < 2:
        sys.exit(f"FAIL: {len(many)} snapshots in the series, {len(one)} on one process")
    for a, b in zip(one, many):
        ida, xa, va = read(a)
        idb, xb, vb = read(b)
        if len(np.unique(idb)) != len(idb) or not np.array_equal(ida, idb):
            sys.exit(f"FAIL: {b}: {len(idb)} particles, {len(np.unique(idb))} distinct ids; one process has {len(ida)}")
        dx = np.max(np.abs(xa - xb)) / np.max(np.abs(xa))
        dv = np.max(np.abs(va - vb)) / max(np.max(np.abs(va)), 1e-300)
        if dx > 1e-12 or dv > 1e-12:
            sys.exit(f"FAIL: {b}: positions deviate by {dx:.3g}, velocities by {dv:.3g}")
        print(f"{os.path.basename(b)}: {len(idb)} particles, each once; deviation x {dx:.2g}, v {dv:.2g}")
    print("PASS")


if __name__ == "__main__":
    main()
