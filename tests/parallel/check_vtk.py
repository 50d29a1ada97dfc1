#!/usr/bin/env python3
"""The VTK series of a distributed run, read by ParaView's readers
(python3-vtk9, the real `vtk` module):
  - the one-process series lists .vtp files and no .pvtp is written;
  - the N-process series lists one .pvtp per snapshot, whose PPointData and
    PPoints declare exactly the arrays (name, type, components) each of its
    N pieces holds; vtkXMLPPolyDataReader reads it without an error and sees
    every particle exactly once (the ids of the one-process snapshot, none
    twice), with the same positions, velocities and stresses by id to 1e-12;
  - the grid series (NAME_grid.pvd) of both runs: the same images, and the
    nodal mass, velocity and force equal to 1e-12 of each array's largest
    magnitude (nonzero in the last snapshot; the first, before any step,
    is all zeros).
Usage: check_vtk.py DIR_ONE_PROCESS NAME_ONE DIR_N NAME_N NP
       check_vtk.py --series DIR NAME PARTICLES [--empty]
The second form checks any distributed series: each entry of NAME.pvd, a
.pvtp (its pieces present and declared exactly) or a .vtp, holds PARTICLES
particles, each once, and the directory holds no piece that no listed
.pvtp names (a continued run removes the snapshots after its checkpoint,
pieces included). With --empty some piece must be empty: a process without
particles writes a valid empty .vtp."""
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

TOL = 1e-12


def fail(msg):
    sys.exit("FAIL: " + msg)


def series(d, name):
    root = ET.parse(os.path.join(d, name + ".pvd")).getroot()
    return [os.path.join(d, ds.get("file")) for ds in root.iter("DataSet")]


def update(reader, path):
    """Update a reader, failing on any error VTK reports (readers report
    errors through events, not exceptions)."""
    errors = []
    reader.AddObserver("ErrorEvent", lambda obj, ev: errors.append(ev))
    reader.GetExecutive().AddObserver("ErrorEvent", lambda obj, ev: errors.append(ev))
    reader.SetFileName(path)
    reader.Update()
    if errors or reader.GetErrorCode() != 0:
        fail(f"{path}: VTK's reader reported an error")
    return reader.GetOutput()


def declared(header, tag):
    """(name, type, components) of every `tag` element in an XML header"""
    out = []
    for m in re.finditer(r"<%s ([^>]*)>" % tag, header):
        a = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        out.append((a["Name"], a["type"], int(a.get("NumberOfComponents", "1"))))
    return out


def piece_arrays(path):
    """the point-data arrays and points of a .vtp, from its XML header (the
    part before the appended binary data)"""
    with open(path, "rb") as f:
        head = f.read().split(b"<AppendedData")[0].decode()
    point_data = head.split("<PointData>")[1].split("</PointData>")[0]
    points = head.split("<Points>")[1].split("</Points>")[0]
    return declared(point_data, "DataArray"), declared(points, "DataArray")


def check_declarations(pvtp, nproc=None):
    """the .pvtp names its pieces (nproc of them, when given), each present,
    whose arrays it declares exactly"""
    root = ET.parse(pvtp).getroot()
    if root.get("type") != "PPolyData":
        fail(f"{pvtp}: type {root.get('type')}, not PPolyData")
    ppd = [(a.get("Name"), a.get("type"), int(a.get("NumberOfComponents"))) for a in root.find("PPolyData/PPointData")]
    ppts = [(a.get("Name"), a.get("type"), int(a.get("NumberOfComponents"))) for a in root.find("PPolyData/PPoints")]
    pieces = [os.path.join(os.path.dirname(pvtp), p.get("Source")) for p in root.iter("Piece")]
    if nproc is not None and len(pieces) != nproc:
        fail(f"{pvtp}: {len(pieces)} pieces for {nproc} processes")
    for p in pieces:
        if not os.path.isfile(p):
            fail(f"{pvtp}: its piece {p} is missing")
        pd, pts = piece_arrays(p)
        if pd != ppd or pts != ppts:
            fail(f"{pvtp}: declares {ppd} {ppts}; the piece {p} holds {pd} {pts}")
    return pieces


def particles(out, path):
    pd = out.GetPointData()
    if out.GetNumberOfPoints() == 0:
        return np.zeros(0, dtype=np.int64), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 6))
    ids = vtk_to_numpy(pd.GetArray("id"))
    order = np.argsort(ids, kind="stable")
    x = vtk_to_numpy(out.GetPoints().GetData())[order]
    v = vtk_to_numpy(pd.GetArray("velocity"))[order]
    s = vtk_to_numpy(pd.GetArray("stress"))[order]
    if out.GetNumberOfVerts() != len(ids):
        fail(f"{path}: {out.GetNumberOfVerts()} vertex cells for {len(ids)} points")
    return ids[order], x, v, s


def read_vtp(path):
    return particles(update(vtk.vtkXMLPolyDataReader(), path), path)


def read_pvtp(path):
    return particles(update(vtk.vtkXMLPPolyDataReader(), path), path)


def rel(a, b):
    scale = np.max(np.abs(a))
    return np.max(np.abs(a - b)) / scale if scale > 0 else np.max(np.abs(b), initial=0.0)


def check_particles(one, many, nproc):
    for a, b in zip(one, many):
        if not a.endswith(".vtp") or not b.endswith(".pvtp"):
            fail(f"the series list {os.path.basename(a)} and {os.path.basename(b)}: expected a .vtp and a .pvtp")
        pieces = check_declarations(b, nproc)
        ida, xa, va, sa = read_vtp(a)
        idb, xb, vb, sb = read_pvtp(b)
        if len(np.unique(idb)) != len(idb) or not np.array_equal(ida, idb):
            fail(f"{b}: {len(idb)} particles, {len(np.unique(idb))} distinct ids; one process has {len(ida)}")
        dx, dv, ds = rel(xa, xb), rel(va, vb), rel(sa, sb)
        if max(dx, dv, ds) > TOL:
            fail(f"{b}: positions deviate by {dx:.3g}, velocities by {dv:.3g}, stresses by {ds:.3g}")
        sizes = [len(read_vtp(p)[0]) for p in pieces]
        print(f"{os.path.basename(b)}: {len(idb)} particles in pieces of {sizes}, each once; deviation x {dx:.2g}, "
              f"v {dv:.2g}, stress {ds:.2g}")


def check_grid(d1, n1, dn, nn):
    one, many = series(d1, n1 + "_grid"), series(dn, nn + "_grid")
    if len(one) != len(many) or not one:
        fail(f"{len(many)} grid snapshots, {len(one)} on one process")
    for a, b in zip(one, many):
        ga, gb = update(vtk.vtkXMLImageDataReader(), a), update(vtk.vtkXMLImageDataReader(), b)
        if ga.GetExtent() != gb.GetExtent() or ga.GetOrigin() != gb.GetOrigin() or ga.GetSpacing() != gb.GetSpacing():
            fail(f"{b}: extent {gb.GetExtent()}, origin {gb.GetOrigin()}; one process {ga.GetExtent()}, {ga.GetOrigin()}")
        worst = {}
        for name in ("mass", "velocity", "force"):
            xa = vtk_to_numpy(ga.GetPointData().GetArray(name))
            xb = vtk_to_numpy(gb.GetPointData().GetArray(name))
            if b == many[-1] and np.max(np.abs(xa)) == 0:
                fail(f"{a}: {name} is zero everywhere: nothing to compare")
            worst[name] = rel(xa, xb)
            if worst[name] > TOL:
                fail(f"{b}: nodal {name} deviates by {worst[name]:.3g}")
        print(f"{os.path.basename(b)}: {ga.GetNumberOfPoints()} nodes; deviation " +
              ", ".join(f"{k} {v:.2g}" for k, v in worst.items()))


def check_series(d, name, count, want_empty):
    snaps = series(d, name)
    if not snaps:
        fail(f"{d}/{name}.pvd lists no snapshot")
    empty, named = 0, set()
    for b in snaps:
        if b.endswith(".pvtp"):
            pieces = check_declarations(b)
            named.update(os.path.basename(p) for p in pieces)
            sizes = [len(read_vtp(p)[0]) for p in pieces]
            empty += sizes.count(0)
            ids = read_pvtp(b)[0]
        else:
            sizes, ids = [], read_vtp(b)[0]
        if len(ids) != count or len(np.unique(ids)) != count:
            fail(f"{b}: {len(ids)} particles, {len(np.unique(ids))} distinct; expected {count}")
        print(f"{os.path.basename(b)}: {count} particles" + (f" in pieces of {sizes}" if sizes else ", one file"))
    stray = sorted(f for f in os.listdir(d) if re.fullmatch(re.escape(name) + r"_\d{6}_p\d+\.vtp", f) and f not in named)
    if stray:
        fail(f"pieces no listed .pvtp names: {stray}")
    if want_empty and empty == 0:
        fail("no piece was empty: the case does not test empty processes")
    print("PASS")


def main():
    if sys.argv[1] == "--series":
        check_series(sys.argv[2], sys.argv[3], int(sys.argv[4]), "--empty" in sys.argv[5:])
        return
    d1, n1, dn, nn, nproc = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
    one, many = series(d1, n1), series(dn, nn)
    if len(one) != len(many) or len(one) < 2:
        fail(f"{len(many)} snapshots in the series, {len(one)} on one process")
    stray = [f for f in os.listdir(d1) if f.endswith(".pvtp")]
    if stray:
        fail(f"the one-process run wrote {stray}")
    check_particles(one, many, nproc)
    check_grid(d1, n1, dn, nn)
    print("PASS")


if __name__ == "__main__":
    main()
