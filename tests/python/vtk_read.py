#!/usr/bin/python3
"""moraine: read the .vtp/.pvd files moraine writes, with VTK's own reader.

Run with Debian's /usr/bin/python3 (python3-vtk9 and numpy). As a library:

    points, arrays = read_vtp("out/p_000010.vtp")   # (N, 3), {name: (N,) or (N, ncomp)}
    series = read_pvd("out/p.pvd")                  # [(time, absolute .vtp path), ...]
    t = time_value("out/p_000010.vtp")              # its TimeValue field data, or None
    points, arrays, t = read_vtkhdf("out/p_000010.vtkhdf")

As a command:

    vtk_read.py summary FILE.vtp   -> {"file": ..., "points": N, "arrays": {name: ncomp, ...}}
    vtk_read.py pvd FILE.pvd       -> [[time, path], ...]
"""

import json
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util import numpy_support


class VtkReadError(Exception):
    pass


def _read_polydata(path):
    """The vtkPolyData in `path`; VTK only prints reader errors, so they are
    collected through an observer and raised instead."""
    if not os.path.isfile(path):
        raise VtkReadError(f"{path}: no such file")
    errors = []
    reader = vtk.vtkXMLPolyDataReader()
    reader.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    # messages of the XML parser behind the reader go to the global output window
    # (and to VTK's logger on stderr, silenced here since the error is raised)
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
        raise VtkReadError(f"{path}: VTK could not read the file: {text or 'error'}")
    return reader.GetOutput()


def _to_numpy(vtk_array, ncomp_hint):
    if vtk_array is None:
        return np.zeros((0, ncomp_hint)) if ncomp_hint > 1 else np.zeros((0,))
    values = numpy_support.vtk_to_numpy(vtk_array)
    ncomp = vtk_array.GetNumberOfComponents()
    if ncomp > 1:
        values = values.reshape(-1, ncomp)
    return values


def read_vtp(path):
    """(points (N, 3) float64, {name: (N,) or (N, ncomp) array})."""
    poly = _read_polydata(path)
    n = poly.GetNumberOfPoints()
    pts = poly.GetPoints()
    points = _to_numpy(pts.GetData(), 3) if pts is not None else np.zeros((0, 3))
    points = points.reshape(n, 3)
    arrays = {}
    pd = poly.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        a = pd.GetAbstractArray(i)
        arrays[a.GetName()] = _to_numpy(a, a.GetNumberOfComponents())
    return points, arrays


def time_value(path):
    """the TimeValue field data of a .vtp as VTK reads it, or None"""
    fd = _read_polydata(path).GetFieldData()
    a = fd.GetArray("TimeValue") if fd is not None else None
    return None if a is None else float(a.GetValue(0))


def read_vtkhdf(path):
    """(points, arrays, TimeValue or None) of a .vtkhdf read by vtkHDFReader"""
    if not os.path.isfile(path):
        raise VtkReadError(f"{path}: no such file")
    reader = vtk.vtkHDFReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None:
        raise VtkReadError(f"{path}: vtkHDFReader could not read the file")
    n = grid.GetNumberOfPoints()
    pts = grid.GetPoints()
    points = _to_numpy(pts.GetData(), 3).reshape(n, 3) if pts is not None and n else np.zeros((0, 3))
    pd = grid.GetPointData()
    arrays = {pd.GetArrayName(i): _to_numpy(pd.GetArray(i), pd.GetArray(i).GetNumberOfComponents())
              for i in range(pd.GetNumberOfArrays())}
    cells = [grid.GetCellType(i) for i in range(grid.GetNumberOfCells())]
    if any(c != vtk.VTK_VERTEX for c in cells) or len(cells) != n:
        raise VtkReadError(f"{path}: expected one vertex cell per point")
    t = grid.GetFieldData().GetArray("TimeValue")
    return points, arrays, (None if t is None else float(t.GetValue(0)))


def read_pvd(path):
    """[(time, absolute path of the data file)] in file order."""
    base = os.path.dirname(os.path.abspath(path))
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        raise VtkReadError(f"{path}: not a VTK collection")
    series = []
    for ds in root.iter("DataSet"):
        series.append((float(ds.get("timestep")), os.path.normpath(os.path.join(base, ds.get("file")))))
    return series


def summary(path):
    points, arrays = read_vtp(path)
    comps = {name: (1 if a.ndim == 1 else int(a.shape[1])) for name, a in arrays.items()}
    return {"file": path, "points": int(points.shape[0]), "arrays": comps}


def main(argv):
    usage = "usage: vtk_read.py summary FILE.vtp | vtk_read.py pvd FILE.pvd"
    if len(argv) != 3 or argv[1] not in ("summary", "pvd"):
        print(usage, file=sys.stderr)
        return 2
    try:
        if argv[1] == "summary":
            result = summary(argv[2])
        else:
            result = [[t, f] for t, f in read_pvd(argv[2])]
    except (VtkReadError, OSError, ET.ParseError) as e:
        print(f"vtk_read.py: {e}", file=sys.stderr)
        return 1
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
