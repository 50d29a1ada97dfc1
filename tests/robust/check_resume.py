#!/usr/bin/python3
"""moraine: the outputs of a run interrupted and resumed (directory B) equal
those of a straight run (directory A): the same files, every .vtp
byte-identical and read by VTK, the .pvd listing the same (time, file)
entries, the CSV row for row, the HDF5 series dataset for dataset.
Checkpoints, provenance and the test's own files are left out.

usage: check_resume.py A B"""
import csv
import os
import re
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import vtk

SKIP = re.compile(r"(_interrupted\.h5|_checkpoint_\d+\.h5|^provenance$|^at_stop$|^stderr.*\.txt$|^\.)")


def outputs(d):
    return sorted(f for f in os.listdir(d) if not SKIP.search(f))


def pvd_entries(path):
    root = ET.parse(path).getroot()
    return [(float(e.get("timestep")), e.get("file")) for e in root.iter("DataSet")]


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def series(path):
    with h5py.File(path, "r") as f:
        return {k: f[k][:] for k in f}, {k: f.attrs[k] for k in f.attrs}


def read_vtp(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput().GetNumberOfPoints()


def main(a, b):
    fails = []
    fa, fb = outputs(a), outputs(b)
    if fa != fb:
        fails.append("files differ: only in straight %s, only in resumed %s" % (sorted(set(fa) - set(fb)),
                                                                                 sorted(set(fb) - set(fa))))
    vtps = [f for f in fa if f.endswith(".vtp") and f in fb]
    for f in vtps:
        with open(os.path.join(a, f), "rb") as x, open(os.path.join(b, f), "rb") as y:
            if x.read() != y.read():
                fails.append("%s differs" % f)
        if read_vtp(os.path.join(b, f)) <= 0:
            fails.append("%s: VTK reads no points" % f)
    for f in (f for f in fa if f.endswith(".pvd")):
        ea, eb = pvd_entries(os.path.join(a, f)), pvd_entries(os.path.join(b, f))
        if ea != eb:
            fails.append("%s: %d entries, resumed %d, or different ones" % (f, len(ea), len(eb)))
        missing = [e[1] for e in eb if not os.path.exists(os.path.join(b, e[1]))]
        if missing:
            fails.append("%s lists missing files %s" % (f, missing[:3]))
    for f in (f for f in fa if f.endswith(".csv")):
        ra, rb = csv_rows(os.path.join(a, f)), csv_rows(os.path.join(b, f))
        bad = [i for i in range(min(len(ra), len(rb))) if ra[i] != rb[i]]
        if len(ra) != len(rb) or bad:
            fails.append("%s: %d rows, resumed %d, first different row %s" % (f, len(ra), len(rb), bad[:1]))
    for f in (f for f in fa if f.endswith(".h5")):
        (da, aa), (db, ab) = series(os.path.join(a, f)), series(os.path.join(b, f))
        if list(da) != list(db):
            fails.append("%s: datasets %s, resumed %s" % (f, list(da), list(db)))
        for k in (k for k in da if k in db):
            if da[k].shape != db[k].shape or not np.array_equal(da[k], db[k], equal_nan=da[k].dtype.kind == "f"):
                fails.append("%s: /%s differs (%d rows, resumed %d)" % (f, k, len(da[k]), len(db[k])))
        if {k: v for k, v in aa.items()}.keys() != ab.keys():
            fails.append("%s: root attributes differ" % f)
    rows = len(csv_rows(os.path.join(a, "diagnostics.csv"))) - 1 if "diagnostics.csv" in fa else 0
    print("compared %d files: %d .vtp byte for byte, %d CSV rows, %d series" %
          (len(fa), len(vtps), rows, len([f for f in fa if f.endswith(".h5")])))
    for m in fails:
        print("FAIL:", m)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
