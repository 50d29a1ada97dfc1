#!/usr/bin/python3
"""moraine: run the verification cases and write the validation report.

usage: report.py [--run] [--render] [--only KEY,...] --moraine EXE --build DIR [--out DIR]

  --run      run every case of scripts/validation/cases.toml: a deck case as
             `EXE DECK -q -o OUT/KEY --set ...`, a ctest case as
             `ctest --test-dir DIR -R REGEX`; each run's output goes to
             OUT/KEY.log and its exit status and run time to OUT/KEY.json
  --render   read OUT/*.log and write doc/validation.md and doc/figures/KEY.png
  (neither: both)
  --only     only these cases (for trying one; the report then lacks the others)
  --out      run directory (default: out/validate in the source tree)

A deck reports its figures as lines "RESULT {json}" (lua/moraine/results.lua);
the report shows each of them with its reference, tolerance and status, so
nothing in the table is typed by hand. Uses Debian's python3 with numpy,
matplotlib and python3-vtk9 (for the collapse picture).
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = os.path.join(ROOT, "scripts", "validation", "cases.toml")
REPORT = os.path.join(ROOT, "doc", "validation.md")
FIGURES = os.path.join(ROOT, "doc", "figures")
sys.path.insert(0, os.path.join(ROOT, "scripts", "validation"))

import plots  # noqa: E402  (scripts/validation/plots.py)


def load_cases():
    with open(CASES, "rb") as f:
        cases = tomllib.load(f)["case"]
    keys = [c["key"] for c in cases]
    dup = {k for k in keys if keys.count(k) > 1}
    if dup:
        raise SystemExit(f"{CASES}: duplicate keys {sorted(dup)}")
    for c in cases:
        if ("deck" in c) == ("ctest" in c):
            raise SystemExit(f"{CASES}: case {c['key']} needs exactly one of deck and ctest")
    return cases


# ---------------------------------------------------------------- running

def run_case(case, moraine, build, out):
    log = os.path.join(out, case["key"] + ".log")
    if "deck" in case:
        # a fresh directory: moraine refuses to write over an earlier report's outputs
        shutil.rmtree(os.path.join(out, case["key"]), ignore_errors=True)
        cmd = [moraine, os.path.join(ROOT, case["deck"]), "-q", "-o", os.path.join(out, case["key"])]
        for a in case.get("args", []):
            cmd += ["--set", a]
    else:
        cmd = ["ctest", "--test-dir", build, "-R", case["ctest"], "--output-on-failure"]
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    start = time.monotonic()
    with open(log, "w") as f:
        rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=ROOT, env=env).returncode
    seconds = time.monotonic() - start
    # the command to reproduce the run by hand, from the source tree
    if "deck" in case:
        shown = ["build/moraine", case["deck"], "-q", "-o", "out/" + case["key"]]
        shown += [w for a in case.get("args", []) for w in ("--set", a)]
    else:
        shown = ["ctest", "--test-dir", "build", "-R", "'" + case["ctest"] + "'"]
    with open(os.path.join(out, case["key"] + ".json"), "w") as f:
        # the load average tells whether other jobs shared the machine during the run
        json.dump({"exit": rc, "seconds": seconds, "command": shown, "load": os.getloadavg()[0]}, f)
    print(f"{case['key']:<28} exit {rc}  {seconds:7.1f} s", flush=True)


# ---------------------------------------------------------------- reading

def read_run(case, out):
    """(run info, [records], log lines) of one case; run info None when never run"""
    info_path = os.path.join(out, case["key"] + ".json")
    if not os.path.isfile(info_path):
        return None, [], []
    with open(info_path) as f:
        info = json.load(f)
    with open(os.path.join(out, case["key"] + ".log"), errors="replace") as f:
        lines = f.read().splitlines()
    records = [json.loads(l[len("RESULT "):]) for l in lines if l.startswith("RESULT {")]
    return info, records, lines


def ctest_counts(lines):
    """(passed, total) from ctest's summary line"""
    for l in lines:
        if "tests passed," in l and "out of" in l:  # "100% tests passed, 0 tests failed out of 7"
            failed = int(l.split("tests passed,")[1].split()[0])
            total = int(l.rsplit("out of", 1)[1].split()[0])
            return total - failed, total
    return 0, 0


# ---------------------------------------------------------------- formatting

def num(x):
    if x is None:
        return "-"
    if isinstance(x, bool):
        return str(x).lower()
    if x == 0:
        return "0"
    a = abs(x)
    if 1e-3 <= a < 1e5:
        s = f"{x:.4g}"
    else:
        s = f"{x:.2e}"
    return s


def with_unit(x, unit):
    u = unit or ""
    if u == "%":
        return num(x) + " %"
    return num(x) + (" " + u if u else "")


def tolerance_text(r):
    parts = []
    if r.get("rtol") is not None or r.get("atol") is not None:
        t = []
        if r.get("rtol"):
            t.append(f"{100 * r['rtol']:.3g} %")
        if r.get("atol"):
            t.append(with_unit(r["atol"], r.get("unit")))
        parts.append("± " + " + ".join(t))
    lo, hi = r.get("min"), r.get("max")
    if lo is not None and hi is not None:
        parts.append(f"{with_unit(lo, r.get('unit'))} to {with_unit(hi, r.get('unit'))}")
    elif hi is not None:
        parts.append("≤ " + with_unit(hi, r.get("unit")))
    elif lo is not None:
        parts.append("≥ " + with_unit(lo, r.get("unit")))
    return ", ".join(parts) or "-"


def moraine_text(r):
    s = with_unit(r["value"], r.get("unit"))
    if r.get("reference") is not None:
        s += f" (reference {with_unit(r['reference'], r.get('unit'))}"
        if r.get("error") is not None:
            s += f", {100 * r['error']:.3g} % off"
        s += ")"
    return s


STATUS = {"pass": "pass", "fail": "**FAIL**", "not reached": "**not reached**", "reported": "reported"}


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def case_rows(case, info, records, lines, figure):
    """table rows of one case and its overall status"""
    link = f"[{cell(case['name'])}](#{case['key']})"
    plot = f"[plot](figures/{figure})" if figure else ""
    rows, statuses = [], []

    def row(what, moraine, tol, status):
        first = not rows
        rows.append([link if first else "", cell(case["reference"]) if first else "", cell(what), cell(moraine),
                     cell(tol), STATUS.get(status, status), plot if first else ""])
        statuses.append(status)

    if info is None:
        row("not run", "-", "-", "fail")
        return rows, statuses
    if "ctest" in case:
        passed, total = ctest_counts(lines)
        ok = info["exit"] == 0 and total > 0
        row(f"ctest `{case['ctest']}`", f"{passed} of {total} tests pass", case.get("tolerance", "-"),
            "pass" if ok else "fail")
        return rows, statuses
    for r in records:
        if r.get("detail"):
            continue  # data points of a plot: listed in the case's section
        what = r.get("what", r["id"])
        row(what, moraine_text(r), tolerance_text(r), r["status"])
    if info["exit"] != 0:
        err = next((l for l in reversed(lines) if l.strip() and not l.startswith("RESULT")), "")
        row("the run", f"exited with status {info['exit']}: {err.strip()[:200]}", "exit 0", "fail")
    elif not records:
        row("the run", "printed no RESULT line", "-", "fail")
    return rows, statuses


# ---------------------------------------------------------------- rendering

HEADER = """# Validation

<!-- Generated by scripts/validation/report.py from the runs of `make validate`
     (scripts/validate.sh); do not edit by hand: edit scripts/validation/cases.toml
     or the decks, and rerun. -->

Each verification case, its reference, what moraine gets, the tolerance and
whether it holds. Every figure below is printed by the run itself (a
`RESULT` line of `lua/moraine/results.lua`; the test decks print them through
`T.expect` in `tests/decks/testlib.lua`, which is also what makes the ctest
tests fail), and this page is written from those lines by
`scripts/validation/report.py`. A case that does not reach its reference says
so: **not reached** marks a target the run reports but does not hold itself
to; **FAIL** a figure outside a tolerance the test suite asserts.

Regenerate the whole report (runs the full-length cases, then rewrites this
page and `doc/figures/`):

    cmake --build build --target validate        # or: scripts/validate.sh

The quick versions of the same decks run and assert in `scripts/test.sh`
(ctest). One case by hand: the command in its section below, from the
source tree, with `build/moraine`.
"""


def render(cases, out, only):
    os.makedirs(FIGURES, exist_ok=True)
    table = ["| case | reference | figure | moraine | tolerance | status | plot |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    sections, counts, total_seconds, loads = [], {}, 0.0, []
    runs = {c["key"]: read_run(c, out) for c in cases}
    for case in cases:
        info, records, lines = runs[case["key"]]
        figure = None
        if case.get("figure") and info is not None:
            figure = plots.draw(case["figure"], case, out, records, runs, FIGURES)
        rows, statuses = case_rows(case, info, records, lines, figure)
        table += ["| " + " | ".join(r) + " |" for r in rows]
        for s in statuses:
            counts[s] = counts.get(s, 0) + 1
        sec = [f"### {case['name']}", f'<a id="{case["key"]}"></a>', ""]
        sec.append(f"Reference: {case['reference']}. Test: {case.get('test', '-')}.")
        if info is not None:
            total_seconds += info["seconds"]
            loads.append(info.get("load", 0.0))
            cmd = " ".join(info["command"])
            sec += ["", f"Reproduce ({info['seconds']:.0f} s in the last run): `{cmd}`"]
        if case.get("note"):
            sec += [""] + "\n\n".join(case["note"].strip().split("\n")).split("\n")  # a paragraph per line
        details = [r for r in records if r.get("detail")]
        if details:
            sec += ["", "Data points: " + "; ".join(f"{r.get('what', r['id'])} = {moraine_text(r)}"
                                                    for r in details) + "."]
        if figure:
            sec += ["", f"![{case['name']}](figures/{figure})"]
        sections.append("\n".join(sec))
    summary = ", ".join(f"{n} {STATUS.get(s, s).strip('*')}" for s, n in sorted(counts.items()))
    text = [HEADER,
            f"Last run: {len(cases)} cases, {sum(counts.values())} figures: {summary}; "
            f"{total_seconds / 60:.0f} min of run time on the 2-core development machine "
            f"(mean 1-minute load average {sum(loads) / max(len(loads), 1):.1f}: "
            "other jobs shared the machine when it is above 2).",
            "", "## Summary", ""] + table + ["", "## Cases", ""]
    text += ["\n\n".join(sections), "",
             "## Not yet covered", "",
             "The cases of the implicit solver (001, [implicit.md](implicit.md)): their decks and tests are",
             "being completed; they join this report as `[[case]]` entries of `scripts/validation/cases.toml`",
             "(see the hook there).",
             ""]
    if only:
        print("--only: doc/validation.md not written (it would lack the other cases)")
        return counts
    with open(REPORT, "w") as f:
        f.write("\n".join(text))
    print(f"wrote {os.path.relpath(REPORT, ROOT)}: {summary}")
    return counts


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--run", action="store_true")
    ap.add_argument("--render", action="store_true")
    ap.add_argument("--only", default="")
    ap.add_argument("--moraine", default=os.path.join(ROOT, "build", "moraine"))
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "validate"))
    a = ap.parse_args(argv)
    if not a.run and not a.render:
        a.run = a.render = True
    cases = load_cases()
    only = [k for k in a.only.split(",") if k]
    if only:
        unknown = set(only) - {c["key"] for c in cases}
        if unknown:
            raise SystemExit(f"--only: no case {sorted(unknown)} in {CASES}")
    a.out = os.path.abspath(a.out)
    os.makedirs(a.out, exist_ok=True)
    if a.run:
        start = time.monotonic()
        for case in cases:
            if not only or case["key"] in only:
                run_case(case, os.path.abspath(a.moraine), os.path.abspath(a.build), a.out)
        print(f"all runs: {(time.monotonic() - start) / 60:.1f} min")
    if a.render:
        counts = render(cases if not only else [c for c in cases if c["key"] in only], a.out, only)
        return 1 if counts.get("fail") else 0
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
