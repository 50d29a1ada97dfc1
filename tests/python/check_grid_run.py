#!/usr/bin/python3
"""moraine: the grid snapshots (.vti) of a run, read with VTK's own reader.

usage: check_grid_run.py OUTDIR SERIES NX NY

Every file the SERIES_grid.pvd lists opens with vtkXMLImageDataReader, has
(NX+1) x (NY+1) x 1 points (a 2D run), the arrays mass (1), velocity (3) and
force (3), and its total nodal mass equals the particles' total mass of
diagnostics.csv (mass is conserved by P2G to round-off). The first file is
the state before any step, when nothing has been mapped yet, and is skipped
for the mass check."""
import csv
import os
import sys

import numpy as np
import vtk
from vtk.util import numpy_support

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtk_read import read_pvd  # noqa: E402
from checklib import Checks  # noqa: E402

outdir, series, nx, ny = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
check = Checks("check_grid_run")


with open(os.path.join(outdir, "diagnostics.csv")) as f:
    total_mass = float(next(csv.DictReader(f))["mass"])
entries = read_pvd(os.path.join(outdir, series + "_grid.pvd"))
check(len(entries) >= 2, f"{len(entries)} grid files")
for k, (t, path) in enumerate(entries):
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    img = reader.GetOutput()
    check(img.GetDimensions() == (nx + 1, ny + 1, 1), f"{path}: dimensions {img.GetDimensions()}")
    pd = img.GetPointData()
    arrays = {pd.GetArrayName(i): pd.GetArray(i) for i in range(pd.GetNumberOfArrays())}
    for name, ncomp in (("mass", 1), ("velocity", 3), ("force", 3)):
        check(name in arrays and arrays[name].GetNumberOfComponents() == ncomp, f"{path}: array {name}")
    if k > 0 and "mass" in arrays:
        m = numpy_support.vtk_to_numpy(arrays["mass"]).sum()
        check(abs(m - total_mass) <= 1e-12 * total_mass, f"{path}: nodal mass {m} vs particle mass {total_mass}")
sys.exit(check.report())
