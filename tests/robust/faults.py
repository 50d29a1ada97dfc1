#!/usr/bin/env python3
"""moraine robustness: every output file fails once (doc/robustness.md, "Fault injection").

The deck tests/robust/faults.lua writes every kind of output file. It is run
once as it is (the reference, which a SIGINT ends with status 130), then once
per case with the LD_PRELOAD library faultfs (tests/robust/faultfs.c) failing
one operation on one file: open, write, flush (fsync), close or rename, with
ENOSPC (a write then first stores half its bytes, as a disk filling up within
it does) or EIO. Every case must
  - exit with status 3 (an output could not be written, doc/errors.md),
  - print a message naming the file and the system's reason for that errno,
  - leave no temporary file and no file the reference run does not write,
  - leave every file written before the faulted one (in the reference run's
    order) in place, and every file it leaves complete and equal to the
    reference's or to an earlier state of it: .vtp, .vti and the deck copy
    byte for byte, a .pvd listing a prefix of the reference's snapshots that
    all exist, a CSV holding a prefix of the reference's lines, each a whole
    row, an HDF5 series (h5py) holding a prefix of its rows, a checkpoint
    (h5py) with every dataset equal to the reference's;
  - leave the faulted file absent when the fault hit its first write, or as
    the complete earlier version when it hit a rewrite.
The reference's .vtp/.vti files are read back with VTK's XML readers.

usage: faults.py MORAINE WORKDIR [--faultfs LIB] [--only SUBSTRING]
(LIB defaults to libfaultfs.so next to MORAINE, where the build puts it.)
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "faults.lua")
OPS = ("open", "write", "flush", "close", "rename")
REASON = {"ENOSPC": "No space left on device", "EIO": "Input/output error"}
TEMP = re.compile(r"^\.(.+)\.tmp\.\d+$")


class Site:
    """a file, the substring faultfs matches it by, and which call of each operation fails"""

    def __init__(self, final, pattern, nth, rewritten=False, csv=False, appended=False):
        self.final, self.pattern, self.nth, self.rewritten, self.csv = final, pattern, nth, rewritten, csv
        self.appended = appended or csv


SITES = [
    # the run log, opened before the deck runs and appended to a message at a
    # time: the second write is the first message after its header line
    Site("log.txt", "log.txt", {"open": 1, "write": 2, "flush": 1, "close": 1}, appended=True),
    Site("provenance/deck.lua", "deck.lua", {op: 1 for op in OPS}),
    Site("provenance/run.txt", "run.txt", {op: 1 for op in OPS}),
    Site("part_000002.vtp", "part_000002.vtp", {op: 1 for op in OPS}),
    # the third rewrite of an index: the file then lists the two snapshots before
    Site("part.pvd", "part.pvd", {op: 3 for op in OPS}, rewritten=True),
    Site("part_grid_000002.vti", "part_grid_000002.vti", {op: 1 for op in OPS}),
    Site("part_grid.pvd", "part_grid.pvd", {op: 3 for op in OPS}, rewritten=True),
    # the CSV is appended to: its header is the first write, the fourth is the third row;
    # it is synced and closed when the deck ends
    Site("diagnostics.csv", "diagnostics.csv", {"open": 1, "write": 4, "flush": 1, "close": 1}, csv=True),
    # the series is written when created (empty), then rewritten: the second publication
    # (a row's, or the last one when the deck ends)
    Site("diagnostics.h5", "diagnostics.h5", {op: 2 for op in OPS}, rewritten=True),
    Site("state.h5", "state.h5", {op: 1 for op in OPS}),
    Site("resumed_interrupted.h5", "_interrupted.h5", {op: 1 for op in OPS}),
]


def cases():
    """(name, site, op, errno name, extra environment)"""
    for site in SITES:
        for op, nth in site.nth.items():
            for err in ("ENOSPC", "EIO"):
                env = {"FAULT_PATH": site.pattern, "FAULT_OP": op, "FAULT_ERRNO": err, "FAULT_NTH": str(nth)}
                if op == "write" and err == "ENOSPC":
                    env["FAULT_SHORT"] = "1"
                yield f"{site.final}.{op}.{err}", site, op, err, env
    # the disk fills up after the checkpoint and stays full: the series' last rewrite, when
    # the deck ends, fails
    series = next(s for s in SITES if s.final == "diagnostics.h5")
    for err in ("ENOSPC", "EIO"):
        env = {"FAULT_PATH": "diagnostics.h5", "FAULT_OP": "write", "FAULT_ERRNO": err, "FAULT_ARM": "state.h5",
               "FAULT_REPEAT": "1"}
        yield f"diagnostics.h5.last.{err}", series, "last", err, env


def run(moraine, faultfs, out, env_extra):
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    env = dict(os.environ, LD_PRELOAD=faultfs, **env_extra)
    # a sanitised moraine wants its runtime first among the libraries; faultfs goes before it
    env["ASAN_OPTIONS"] = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"), "verify_asan_link_order=0"]))
    proc = subprocess.run([moraine, DECK, "-q", "-o", out], env=env, capture_output=True, text=True, timeout=120)
    return proc.returncode, proc.stderr


def files_under(out):
    found = {}
    for root, _, names in os.walk(out):
        for name in names:
            path = os.path.join(root, name)
            found[os.path.relpath(path, out)] = path
    return found


def creation_order(trace, out):
    """the output files, relative to out, in the order the reference run first opened them"""
    order = []
    for line in open(trace):
        path = os.path.relpath(os.path.abspath(line.strip()), out)
        head, base = os.path.split(path)
        m = TEMP.match(base)
        rel = os.path.join(head, m.group(1)) if m else path
        if base == ".moraine.lock":  # the run's lock on the directory, removed when it ends
            continue
        if not rel.startswith("..") and rel not in order:
            order.append(rel)
    return order


def read_vtk_files(files):
    """every .vtp/.vti of the reference read back with VTK: point counts"""
    import vtk
    counts = {}
    for rel, path in files.items():
        if rel.endswith((".vtp", ".vti")):
            reader = vtk.vtkXMLPolyDataReader() if rel.endswith(".vtp") else vtk.vtkXMLImageDataReader()
            reader.SetFileName(path)
            reader.Update()
            counts[rel] = reader.GetOutput().GetNumberOfPoints()
    return counts


def pvd_list(path):
    return [d.get("file") for d in ET.parse(path).getroot().iter("DataSet")]


def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
    return found


def same_values(a, b):
    return a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a, b, equal_nan=a.dtype.kind == "f")


def check_file(rel, path, ref_path, files):
    """'' when the file is complete and equal to the reference or an earlier state of it, else why not"""
    if rel.endswith((".vtp", ".vti", ".lua")):
        return "" if open(path, "rb").read() == open(ref_path, "rb").read() else "differs from the reference"
    if rel.endswith(".pvd"):
        listed, ref = pvd_list(path), pvd_list(ref_path)
        if listed != ref[: len(listed)]:
            return f"lists {listed}, not a prefix of {ref}"
        missing = [f for f in listed if os.path.join(os.path.dirname(rel), f) not in files]
        return f"lists missing files {missing}" if missing else ""
    if rel.endswith(".csv"):
        text, ref = open(path).read(), open(ref_path).read()
        if text and not text.endswith("\n"):
            return f"ends in part of a row: {text.splitlines()[-1][:60]!r}..."
        return "" if ref.startswith(text) and text.count("\n") >= 1 else "is not a prefix of the reference's lines"
    if rel == "log.txt":
        text = open(path).read()
        return "" if text.startswith("moraine ") and text.endswith("\n") else "is not whole lines"
    if rel.endswith(".txt"):
        keys = [line.split(":")[0] for line in open(path)]
        ref = [line.split(":")[0] for line in open(ref_path)]
        return "" if keys == ref and open(path).read().endswith("\n") else "is incomplete"
    if rel == "diagnostics.h5":
        got, ref = datasets(path), datasets(ref_path)
        rows = {len(v) for v in got.values()}
        if len(rows) != 1:
            return f"datasets of different lengths {rows}"
        n = rows.pop()
        bad = [k for k in got if k not in ref or not same_values(got[k], ref[k][:n])]
        return f"datasets {bad} differ from the reference's first {n} rows" if bad else ""
    if rel.endswith(".h5"):
        got, ref = datasets(path), datasets(ref_path)
        bad = sorted(set(got) ^ set(ref)) + [k for k in got if k in ref and not same_values(got[k], ref[k])]
        return f"datasets {bad[:5]} differ from the reference" if bad else ""
    return "is not an output the check knows"


def check_case(site, err, left, status, stderr, log, out, ref_files, order):
    """the list of problems of one case; `left`: the faulted file keeps an earlier version"""
    problems = []
    if status != 3:
        problems.append(f"exit status {status}, expected 3")
    want = f"cannot write '{os.path.join(out, site.final)}'"
    if not any(want in line and REASON[err] in line for line in stderr.splitlines()):
        problems.append(f"no message naming {site.final} and '{REASON[err]}'")
    if not os.path.exists(log):
        problems.append("the fault was never injected")
    files = files_under(out)
    for rel, path in files.items():
        if TEMP.match(os.path.basename(rel)):
            problems.append(f"temporary file left: {rel}")
        elif rel not in ref_files:
            problems.append(f"unexpected file {rel}")
        else:
            why = check_file(rel, path, ref_files[rel], files)
            if why:
                problems.append(f"{rel} {why}")
    earlier = order[: order.index(site.final)]
    problems += [f"earlier output {rel} is missing" for rel in earlier if rel not in files]
    if left and site.final not in files:
        problems.append(f"{site.final}: its earlier version is gone")
    if not left and site.final in files:
        problems.append(f"{site.final} exists, though its first write failed")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("moraine")
    ap.add_argument("workdir")
    ap.add_argument("--faultfs")
    ap.add_argument("--only", default="")
    args = ap.parse_args()
    moraine = os.path.abspath(args.moraine)
    faultfs = os.path.abspath(args.faultfs or os.path.join(os.path.dirname(moraine), "libfaultfs.so"))
    work = os.path.abspath(args.workdir)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    ref_out, trace = os.path.join(work, "reference"), os.path.join(work, "reference.trace")
    status, stderr = run(moraine, faultfs, ref_out, {"FAULT_TRACE": trace})
    if status != 130:
        sys.exit(f"the reference run exited with {status}, expected 130:\n{stderr}")
    ref_files = files_under(ref_out)
    order = creation_order(trace, ref_out)
    points = read_vtk_files(ref_files)
    empty = [rel for rel, n in points.items() if n == 0]
    if empty or len(points) != 10:
        sys.exit(f"reference VTK files: {points}")
    print(f"reference: {len(ref_files)} files, {len(points)} VTK files read back; written in the order {order}")

    passed, failed, shown = 0, 0, ""
    for i, (name, site, op, err, env) in enumerate(cases()):
        if args.only not in name:
            continue
        # numbered: a directory named after the file would match faultfs's substring
        out, log = os.path.join(work, f"case{i:03d}", "out"), os.path.join(work, f"case{i:03d}", "fault.log")
        env["FAULT_LOG"] = log
        status, stderr = run(moraine, faultfs, out, env)
        # a rewritten file keeps its earlier version; so does the CSV once it is open
        left = op == "last" or (site.rewritten and site.nth[op] > 1) or (site.appended and op != "open")
        problems = check_case(site, err, left, status, stderr, log, out, ref_files, order)
        said = stderr.strip().replace(out, "OUT").replace("\n", " / ")
        if problems:
            failed += 1
            print(f"FAIL {name}: {'; '.join(problems)}\n     said: {said}")
        else:
            passed += 1
            print(f"ok   {name}: {said}")
        if name == "resumed_interrupted.h5.write.ENOSPC":
            shown = stderr.strip().splitlines()[-1].replace(out, work)
    if shown:  # for doc/errors.md: Ctrl-C on a full disk
        print(f"message: {shown}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed or not passed else 0


if __name__ == "__main__":
    sys.exit(main())
