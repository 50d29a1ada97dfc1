#!/usr/bin/python3
"""moraine: the forms of a particle snapshot and the series' attributes,
read back from the files of tests/decks/vtk_forms.lua.

    moraine tests/decks/vtk_forms.lua -o OUT && check_vtk_forms.py OUT DECK

Checks, with VTK's own readers (python3-vtk9) and xarray (engine h5netcdf):
  - every form of the same state holds the raw Float64 .vtp's values: exactly
    (zlib at levels 6 and 9, VTKHDF), or those values rounded to Float32
    (float32 = true: binary, ascii, zlib, VTKHDF); integers are kept;
  - each file's TimeValue equals its time in the .pvd or .vtkhdf.series;
  - the zlib + Float32 .vtp is at least 3 times smaller than the raw .vtp
    without its TimeValue (the form every .vtp had before): sizes are
    deterministic, so the ratio is a property of the format and the data;
  - the HDF5 series of the two simulations open in xarray over one dimension
    `time` (no phony dimensions), with the 2D units (J/m, kg/m, ...) and the
    run's name, the deck's path and the deck's text as root attributes.
Prints the sizes and ratios of every form."""

import json
import os
import re
import sys

import numpy as np
import xarray

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_read  # noqa: E402
from checklib import Checks  # noqa: E402

check = Checks("check_vtk_forms")

EXACT = ["zlib", "zlib9"]
ROUNDED = ["f32", "zlib_f32", "ascii_f32"]


def as_float32(values):
    return values.astype(np.float32) if values.dtype == np.float64 else values


def same(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b)


def check_values(label, points, arrays, ref_points, ref_arrays, rounded):
    """the values of one form against the raw file's (rounded to Float32 if asked)"""
    conv = as_float32 if rounded else (lambda v: v)
    check(same(points, conv(ref_points)), f"{label}: points")
    check(sorted(arrays) == sorted(ref_arrays), f"{label}: arrays {sorted(arrays)}")
    for name, ref in ref_arrays.items():
        got = arrays.get(name)
        check(got is not None and same(got, conv(ref)), f"{label}: {name}")


def timevalue_matches_collection(path, label):
    """TimeValue of each file listed = its time in the collection"""
    if path.endswith(".pvd"):
        series = vtk_read.read_pvd(path)
        times = [(t, vtk_read.time_value(f)) for t, f in series]
    else:
        with open(path) as f:
            doc = json.load(f)
        check(doc.get("file-series-version") == "1.0", f"{label}: file-series-version")
        base = os.path.dirname(path)
        series = [(e["time"], os.path.join(base, e["name"])) for e in doc["files"]]
        times = [(t, vtk_read.read_vtkhdf(f)[2]) for t, f in series]
    check(len(times) > 0 and all(t == tv for t, tv in times), f"{label}: TimeValue = collection time {times}")
    return series


def check_forms(out):
    forms = os.path.join(out, "forms")
    raw = os.path.join(forms, "raw_000000.vtp")
    ref_points, ref_arrays = vtk_read.read_vtp(raw)
    check(ref_points.dtype == np.float64 and len(ref_points) == 400, "raw: 400 Float64 points")
    for form in EXACT + ROUNDED:
        path = os.path.join(forms, f"{form}_000000.vtp")
        points, arrays = vtk_read.read_vtp(path)
        check_values(form, points, arrays, ref_points, ref_arrays, form in ROUNDED)
        timevalue_matches_collection(os.path.join(forms, f"{form}.pvd"), form)
    for form, rounded in (("vtkhdf", False), ("vtkhdf_zlib_f32", True)):
        points, arrays, _ = vtk_read.read_vtkhdf(os.path.join(forms, f"{form}_000000.vtkhdf"))
        check_values(form, points, arrays, ref_points, ref_arrays, rounded)
        timevalue_matches_collection(os.path.join(forms, f"{form}.vtkhdf.series"), form)
    t_raw = timevalue_matches_collection(os.path.join(forms, "raw.pvd"), "raw")
    check(abs(t_raw[0][0] - 0.3) < 1e-12, f"the snapshot is at the end of the cut-short collapse: {t_raw}")
    return raw


def report_sizes(out, raw):
    """sizes of every form; the zlib + Float32 .vtp >= 3x smaller than today's raw .vtp"""
    with open(raw, "rb") as f:
        text = f.read()
    field = re.search(rb"  <FieldData>.*?</FieldData>\n", text, re.S)
    check(field is not None, "raw: a FieldData element")
    before = len(text) - (len(field.group(0)) if field else 0)  # the raw .vtp as written without TimeValue
    forms = os.path.join(out, "forms")
    print(f"raw Float64 .vtp without TimeValue: {before} bytes; with it: {len(text)}")
    for name in sorted(os.listdir(forms)):
        if re.search(r"_000000\.(vtp|vtkhdf)$", name):
            size = os.path.getsize(os.path.join(forms, name))
            print(f"  {name:32s} {size:8d} bytes  {before / size:5.2f}x smaller")
    zf = os.path.getsize(os.path.join(forms, "zlib_f32_000000.vtp"))
    check(before >= 3 * zf, f"zlib + Float32 .vtp {zf} bytes, {before / zf:.2f}x smaller than {before}")
    check(os.path.getsize(os.path.join(forms, "zlib_000000.vtp")) < before, "zlib alone is smaller")


def check_series(path, run_name, deck):
    """xarray opens the series over `time` alone, with 2D units and the run's record"""
    with xarray.open_dataset(path, engine="h5netcdf") as ds:
        check(dict(ds.sizes) == {"time": ds.sizes.get("time", -1)} and ds.sizes["time"] > 1,
              f"{path}: one dimension time {dict(ds.sizes)}")
        check(all(v.dims == ("time",) for v in ds.data_vars.values()), f"{path}: every variable over time")
        check(not any(d.startswith("phony") for d in ds.dims), f"{path}: no phony dimensions")
        check(np.all(np.diff(ds["time"].values) >= 0), f"{path}: time is the coordinate, increasing")
        units = {name: ds[name].attrs.get("units") for name in ds.variables}
        for name, unit in (("E_kinetic", "J/m"), ("W_MPM", "J/m"), ("mass", "kg/m"), ("momentum_x", "kg m/s/m"),
                           ("angular_z", "kg m^2/s/m"), ("L_centroid", "kg m^2/s/m"), ("com_x", "m"),
                           ("time", "s"), ("dt", "s")):
            check(units.get(name) == unit, f"{path}: {name} in {unit}, got {units.get(name)}")
        attrs = ds.attrs
        check(attrs.get("run_name") == run_name, f"{path}: run_name {attrs.get('run_name')}")
        check(attrs.get("deck_path") == os.path.realpath(deck), f"{path}: deck_path {attrs.get('deck_path')}")
        with open(deck, encoding="utf-8") as f:
            check(attrs.get("deck") == f.read(), f"{path}: the deck's text")


def main():
    if len(sys.argv) != 3:
        print("usage: check_vtk_forms.py OUT DECK", file=sys.stderr)
        return 2
    out, deck = sys.argv[1], sys.argv[2]
    try:
        raw = check_forms(out)
        report_sizes(out, raw)
        zf = timevalue_matches_collection(os.path.join(out, "zf", "p.pvd"), "zlib + Float32 series")
        h5 = timevalue_matches_collection(os.path.join(out, "h5", "p.vtkhdf.series"), "VTKHDF series")
        check(len(zf) == 4 and len(h5) == 4, f"four snapshots in each series ({len(zf)}, {len(h5)})")
        check(zf[-1][0] == h5[0][0], "the VTKHDF series starts where the .vtp one ended")
    except vtk_read.VtkReadError as e:
        check(False, str(e))
    check_series(os.path.join(out, "diagnostics.h5"), "collapse_settle", deck)
    check_series(os.path.join(out, "diagnostics_2.h5"), "collapse_collapse", deck)
    return check.report()


if __name__ == "__main__":
    sys.exit(main())
