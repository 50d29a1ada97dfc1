#!/usr/bin/python3
"""moraine: read the grid files left by `test_vti DIR` with VTK's own reader.

    test_vti DIR && /usr/bin/python3 tests/python/check_vti.py DIR

Checks each .vti's dimensions, origin, spacing, model time, point coordinates
(3D, z = 0 in 2D) and every array against node_value() of
tests/unit/test_vti.c, and the .pvd that lists the 2D files. Needs Debian's
python3-vtk9 and numpy."""

import os
import sys

import numpy as np
import vtk
from vtk.util import numpy_support

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_read  # noqa: E402  (the .pvd parser)
from checklib import Checks  # noqa: E402

ORIGIN = (-1.0, 2.0, 0.5)  # make_grid() in test_vti.c
CELL = 0.5
NCELL = (4, 3, 2)

check = Checks("check_vti")


def read_image(path):
    """The vtkImageData in `path`; reader errors are raised, not only printed."""
    if not os.path.isfile(path):
        raise vtk_read.VtkReadError(f"{path}: no such file")
    errors = []
    reader = vtk.vtkXMLImageDataReader()
    reader.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    output = vtk.vtkStringOutputWindow()
    previous = vtk.vtkOutputWindow.GetInstance()
    verbosity = vtk.vtkLogger.GetCurrentVerbosityCutoff()
    vtk.vtkOutputWindow.SetInstance(output)
    vtk.vtkLogger.SetStderrVerbosity(vtk.vtkLogger.VERBOSITY_OFF)
    try:
        reader.SetFileName(path)
        reader.Update()
    finally:
        vtk.vtkOutputWindow.SetInstance(previous)
        vtk.vtkLogger.SetStderrVerbosity(verbosity)
    text = output.GetOutput().strip()
    if errors or "ERROR" in text:
        raise vtk_read.VtkReadError(f"{path}: VTK could not read the file: {text or 'error'}")
    return reader.GetOutput()


def node_value(a, c, i, j, k):
    """mirror of node_value() in test_vti.c"""
    return (a + 1) * 1000.0 + c * 0.25 + i + 10.0 * j + 100.0 * k + 1.0 / (i + j + k + 3)


def expected(a, ncomp, np_):
    """array a over the domain nodes, x fastest, as (npoints, ncomp)"""
    k, j, i = np.meshgrid(np.arange(np_[2]), np.arange(np_[1]), np.arange(np_[0]), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    cols = [node_value(a, c, i, j, k) for c in range(ncomp)]
    return np.stack(cols, axis=1)


def check_image(path, dim, time):
    label = os.path.basename(path)
    # VTK reads a file cut short in its appended data without a word (the
    # missing values come back as zeros): the end tag shows the file is whole
    with open(path, "rb") as f:
        check(f.read().endswith(b"</VTKFile>\n"), f"{label}: ends with </VTKFile>")
    img = read_image(path)
    np_ = tuple(NCELL[d] + 1 if d < dim else 1 for d in range(3))
    origin = tuple(ORIGIN[d] if d < dim else 0.0 for d in range(3))
    spacing = (CELL, CELL, CELL if dim == 3 else 1.0)
    check(tuple(img.GetDimensions()) == np_, f"{label}: dimensions {img.GetDimensions()}, expected {np_}")
    check(tuple(img.GetOrigin()) == origin, f"{label}: origin {img.GetOrigin()}")
    check(tuple(img.GetSpacing()) == spacing, f"{label}: spacing {img.GetSpacing()}")
    npts = np_[0] * np_[1] * np_[2]
    check(img.GetNumberOfPoints() == npts, f"{label}: {img.GetNumberOfPoints()} points, expected {npts}")

    # every point is 3D; the last one is the far corner of the domain
    pts = np.array([img.GetPoint(n) for n in range(npts)])
    corner = tuple(origin[d] + (np_[d] - 1) * spacing[d] for d in range(3))
    check(pts.shape == (npts, 3) and tuple(pts[-1]) == corner, f"{label}: last point {pts[-1]}, expected {corner}")
    if dim == 2:
        check(np.all(pts[:, 2] == 0.0), f"{label}: z = 0 in 2D")

    pd = img.GetPointData()
    names = sorted(pd.GetArrayName(n) for n in range(pd.GetNumberOfArrays()))
    check(names == ["force", "mass", "velocity"], f"{label}: arrays {names}")
    for a, (name, ncomp) in enumerate((("mass", 1), ("velocity", 3), ("force", 3))):
        arr = pd.GetArray(name)
        if arr is None:
            continue
        values = numpy_support.vtk_to_numpy(arr).reshape(npts, ncomp)
        check(arr.GetNumberOfComponents() == ncomp, f"{label}: {name} has {arr.GetNumberOfComponents()} components")
        check(values.dtype == np.float64, f"{label}: {name} is {values.dtype}")
        # written with all 17 digits or as raw bytes: equal, not only close
        check(np.array_equal(values, expected(a, ncomp, np_)), f"{label}: {name} values")
        check(not np.any(values == -999.0), f"{label}: {name} holds a ghost node")

    fd = img.GetFieldData()
    tv = fd.GetArray("TimeValue") if fd is not None else None
    check(tv is not None and tv.GetNumberOfTuples() == 1 and tv.GetValue(0) == time,
          f"{label}: TimeValue {tv.GetValue(0) if tv is not None else None}, expected {time}")


def main():
    if len(sys.argv) != 2:
        print("usage: check_vti.py DIR", file=sys.stderr)
        return 2
    d = sys.argv[1]
    try:
        check_image(os.path.join(d, "grid2d.vti"), 2, 0.0)
        check_image(os.path.join(d, "grid2d_ascii.vti"), 2, 0.5)
        check_image(os.path.join(d, "grid3d.vti"), 3, 0.25)
        series = vtk_read.read_pvd(os.path.join(d, "grid2d.pvd"))
        check([t for t, _ in series] == [0.0, 0.5], f"pvd times {[t for t, _ in series]}")
        check([os.path.basename(f) for _, f in series] == ["grid2d.vti", "grid2d_ascii.vti"], "pvd files")
        check(all(os.path.isfile(f) for _, f in series), "pvd files exist")
    except (vtk_read.VtkReadError, OSError) as e:
        check(False, str(e))
    return check.report()


if __name__ == "__main__":
    sys.exit(main())
