#!/usr/bin/python3
"""moraine: the files a run killed with SIGKILL leaves are complete or absent.

usage: check_killed_outputs.py DIR [DIR ...]

Every file in each DIR (and below) must be whole and readable:
  .vtp  VTK's vtkXMLPolyDataReader reads it without error;
  .vti  VTK's vtkXMLImageDataReader reads it without error;
  .pvd  parses as a VTK collection, every file it lists exists and is read
        (so a collection never names a file that is not complete);
  .h5   h5py opens it and reads every dataset; a series (format
        "moraine-series") has datasets of one length, and its rows agree
        with the CSV's rows they share (step and time);
  .csv  every line has the header's number of fields, all numbers.
Hidden temporary files (`.NAME.tmp.PID`, left when the kill came during a
write) are allowed: no reader looks at them. They are counted and reported as
the evidence that kills landed in the middle of writing.
Run with Debian's /usr/bin/python3 (python3-vtk9, python3-h5py, numpy)."""

import os
import re
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import vtk_read  # noqa: E402
from checklib import Checks  # noqa: E402
from check_vti import read_image  # noqa: E402

TEMP = re.compile(r"^\..+\.tmp\.\d+$")
check = Checks("check_killed_outputs")


def read_csv(path):
    with open(path) as f:
        lines = f.read().split("\n")
    check(lines[-1] == "", f"{path}: ends with a whole line")
    header = lines[0].split(",")
    rows = []
    for i, line in enumerate(lines[1:-1], start=2):
        fields = line.split(",")
        ok = len(fields) == len(header)
        try:
            rows.append([float(v) for v in fields])
        except ValueError:
            ok = False
        check(ok, f"{path}:{i}: a whole row of {len(header)} numbers")
    return header, np.array(rows)


def read_h5(path, csvs):
    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            obj[...]
    with h5py.File(path, "r") as f:
        f.visititems(visit)
        if f.attrs.get("format", b"") == b"moraine-series":
            lengths = {name: f[name].shape[0] for name in f}
            check(len(set(lengths.values())) == 1, f"{path}: datasets of one length {lengths}")
            csv = csvs.get(os.path.dirname(path))
            if csv is not None:
                header, rows = csv
                n = min(len(rows), f["step"].shape[0])
                ok = n == 0 or (np.array_equal(f["step"][:n], rows[:n, header.index("step")]) and
                                np.array_equal(f["time"][:n], rows[:n, header.index("time")]))
                check(ok, f"{path}: the first {n} rows agree with the CSV")


def check_dir(top):
    temps = 0
    csvs = {}
    files = []
    for root, _, names in os.walk(top):
        for name in names:
            if TEMP.match(name):
                temps += 1
            else:
                files.append(os.path.join(root, name))
    for path in sorted(files, key=lambda p: not p.endswith(".csv")):  # CSVs first, for the series
        try:
            if path.endswith(".vtp"):
                vtk_read.read_vtp(path)
                check(True, path)
            elif path.endswith(".vti"):
                read_image(path)
                check(True, path)
            elif path.endswith(".pvd"):
                series = vtk_read.read_pvd(path)
                for _, listed in series:
                    check(os.path.isfile(listed), f"{path}: lists {listed}, which exists")
            elif path.endswith(".h5"):
                read_h5(path, csvs)
            elif path.endswith(".csv"):
                csvs[os.path.dirname(path)] = read_csv(path)
        except (vtk_read.VtkReadError, OSError, ET.ParseError, KeyError, ValueError) as e:
            check(False, f"{path}: {e}")
    return temps, len(files)


def main(argv):
    total_temps = total_files = 0
    for d in argv[1:]:
        temps, files = check_dir(d)
        total_temps += temps
        total_files += files
    print(f"check_killed_outputs: {total_files} files read in {len(argv) - 1} directories; "
          f"{total_temps} hidden temporary files (kills during a write) ignored")
    return check.report()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
