#!/usr/bin/python3
"""moraine: an HDF5 time series holds the same values as the CSV beside it.

    check_series_h5.py [--extra-columns] SERIES.h5 SERIES.csv [SERIES.h5 SERIES.csv ...]

For each pair, reads the series with h5py and with h5dump (a missing h5dump
is a failure), and checks that:
  - the file is a moraine series (root attribute format = "moraine-series");
  - /time, /step and every column are 1D datasets of the same length, each
    with `units` and `description` attributes;
  - the CSV's columns are the series' columns (step -> /step, time -> /time,
    any other header -> the dataset of that name) and no dataset is missing
    from the CSV (with --extra-columns the series may hold more: values
    recorded from Lua that the CSV does not carry);
  - every value agrees to round-off (NaN where the CSV says nan);
  - xarray (engine h5netcdf) reads the file as variables over one dimension
    `time`, the /time dataset being its coordinate (HDF5 dimension scales).
Run with Debian's /usr/bin/python3 (python3-h5py, numpy, python3-xarray,
python3-h5netcdf)."""

import csv
import math
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklib import Checks  # noqa: E402

RTOL = 4 * np.finfo(np.float64).eps  # both sides come from the same double

check = Checks("check_series_h5")


def text(value):
    """an attribute as str (h5py gives fixed-length strings as bytes)"""
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8")
    return str(value)


def read_csv(path):
    """{header: float64 array}; a last line cut short by a crash is left out"""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    if body and len(body[-1]) != len(header):
        body = body[:-1]
    columns = {}
    for i, name in enumerate(header):
        columns[name] = np.array([float(r[i]) for r in body], dtype=np.float64)
    return columns


def agree(a, b):
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and bool(np.all(np.isclose(a, b, rtol=RTOL, atol=0.0, equal_nan=True)))


def dataset_name(header):
    return header  # step, time and the columns all sit in the root group


def check_h5py(h5_path, columns, label, extra_ok):
    with h5py.File(h5_path, "r") as f:
        check(text(f.attrs.get("format", b"")) == "moraine-series", f"{label}: root attribute format")
        names = sorted(f.keys())
        rows = f["time"].shape[0] if "time" in f else -1
        for name in names:
            ds = f[name]
            check(isinstance(ds, h5py.Dataset) and ds.ndim == 1, f"{label}: /{name} is a 1D dataset")
            check(ds.shape[0] == rows, f"{label}: /{name} has {ds.shape[0]} rows, /time has {rows}")
            check(ds.maxshape == (None,), f"{label}: /{name} is extendable")
            check("units" in ds.attrs and "description" in ds.attrs, f"{label}: /{name} has units and description")
        check(f["step"].dtype == np.int64, f"{label}: /step is int64")
        check(text(f["time"].attrs.get("units", b"")) == "s", f"{label}: /time is in s")
        missing = sorted(set(columns) - set(names))
        extra = sorted(set(names) - set(columns))
        check(not missing, f"{label}: CSV columns without a dataset: {missing}")
        check(extra_ok or not extra, f"{label}: datasets not in the CSV: {extra}")
        for header, values in columns.items():
            name = dataset_name(header)
            if name in f:
                check(agree(f[name][:], values), f"{label}: /{name} (h5py) differs from the CSV")
        return names


def check_xarray(h5_path, columns, label):
    """xarray (engine h5netcdf) sees one dimension `time` whose coordinate is
    /time, every other dataset a variable over it, no phony dimensions"""
    import xarray  # noqa: E402  (python3-xarray, python3-h5netcdf)
    with xarray.open_dataset(h5_path, engine="h5netcdf") as ds:
        check(list(ds.dims) == ["time"], f"{label}: xarray dimensions {list(ds.dims)}")
        check("time" in ds.coords, f"{label}: time is a coordinate")
        for name in ds.data_vars:
            check(ds[name].dims == ("time",), f"{label}: {name} is over time, not {ds[name].dims}")
        for header, values in columns.items():
            if header in ds.variables:
                check(agree(ds[header].values, values), f"{label}: {header} (xarray) differs from the CSV")


def h5dump_values(h5_path, name):
    """the values of dataset /name as h5dump prints them, with 17 digits"""
    out = subprocess.run(["h5dump", "-d", "/" + name, "-m", "%.17g", "-y", "-w0", h5_path],
                         capture_output=True, text=True, check=True).stdout
    data = out[out.index("DATA {") + len("DATA {"):]
    data = data[:data.index("}")]
    values = []
    for token in re.split(r"[,\s]+", data.strip()):
        if token:
            values.append(math.nan if token.lower() in ("nan", "-nan") else float(token))
    return values


def check_h5dump(h5_path, columns, names, label):
    for header, values in columns.items():
        name = dataset_name(header)
        if name not in names:
            continue
        try:
            dumped = h5dump_values(h5_path, name)
        except (subprocess.CalledProcessError, ValueError) as e:
            check(False, f"{label}: h5dump -d /{name}: {e}")
            continue
        check(agree(dumped, values), f"{label}: /{name} (h5dump) differs from the CSV")


def main(argv):
    extra_ok = "--extra-columns" in argv
    argv = [a for a in argv if a != "--extra-columns"]
    if len(argv) < 3 or len(argv) % 2 != 1:
        print("usage: check_series_h5.py [--extra-columns] SERIES.h5 SERIES.csv [SERIES.h5 SERIES.csv ...]",
              file=sys.stderr)
        return 2
    # h5dump (Debian: hdf5-tools, installed by scripts/install-deps.sh) is part of the check
    have_h5dump = shutil.which("h5dump") is not None
    check(have_h5dump, "h5dump is installed (apt-get install hdf5-tools)")
    for h5_path, csv_path in zip(argv[1::2], argv[2::2]):
        label = os.path.basename(h5_path)
        try:
            columns = read_csv(csv_path)
            names = check_h5py(h5_path, columns, label, extra_ok)
            if have_h5dump:
                check_h5dump(h5_path, columns, names, label)
            check_xarray(h5_path, columns, label)
        except (OSError, KeyError, ValueError, IndexError) as e:
            check(False, f"{label}: {e}")
    return check.report()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
