#!/usr/bin/python3
"""moraine: check that check_api_doc.py notices a missing entry of every kind.

usage: check_api_doc_selftest.py MORAINE DOC

For each kind of registered name -- a material model, a shape function, a
motion integration strategy (transfer preset), a stress-update scheme, a
boundary condition, a time-step policy (a key of `simulation{} dt`) and a
deck key (of `simulation{}` and of `add_particles()`) -- it takes one name
from the same sources check_api_doc.py reads, removes that name from a copy
of DOC (every "`name`" code span, and "material.<model>" for a model), and
runs check_api_doc.py on the copy in a scratch tree whose src/ and lua/ are
the real ones. The check passes when the copy gives a FAIL line naming the
removed entry that the original document does not give. Prints one line per
kind; exits 0 when every kind is noticed.
"""
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import check_api_doc as checker  # noqa: E402


def run_checker(moraine, doc):
    r = subprocess.run([sys.executable, os.path.join(HERE, "check_api_doc.py"), moraine, doc],
                       capture_output=True, text=True, timeout=120)
    return [l for l in r.stdout.splitlines() if l.startswith("FAIL: ")], r.returncode


def pick(names, avoid=()):
    for n in names:
        if n not in avoid:
            return n
    raise SystemExit("no name to pick from " + repr(names))


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    moraine, doc = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    root = os.path.dirname(os.path.dirname(doc))
    sources = checker.source_lists(root)
    headings = checker.heading_lists(root)
    groups = checker.list_options(moraine)
    model = headings["material model"][0][0][0].split(".")[-1]  # "mpm.material.<model>"
    cases = [  # (kind, removed name, substitutions, regex the FAIL line must match)
        ("material model", model, [("material." + model, "material.gone_model")],
         r"material model mpm\.material\." + re.escape(model) + " "),
        ("shape function", pick(sources["shape function"][0]), None, r"shape function `{n}`"),
        ("strategy (transfer preset)", pick(sources["transfer preset"][0]), None, r"transfer preset `{n}`"),
        ("stress update", pick(sources["stress update"][0]), None, r"stress update `{n}`"),
        ("boundary condition", pick(sources["boundary kind"][0]), None, r"boundary kind `{n}`"),
        ("time-step policy", pick(groups["simulation{} dt"], avoid=("min", "max")), None,
         r"group 'simulation\{\} dt': key `{n}`"),
        ("deck key of simulation{}", pick(groups["simulation{}"]), None, r"group 'simulation\{\}': key `{n}`"),
        ("deck key of add_particles()", pick(groups["add_particles()"]), None,
         r"group 'add_particles\(\)': key `{n}`"),
    ]
    with open(doc, encoding="utf-8") as f:
        original = f.read()
    baseline, _ = run_checker(moraine, doc)
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for d in ("src", "lua"):
            os.symlink(os.path.join(root, d), os.path.join(tmp, d))
        os.mkdir(os.path.join(tmp, "doc"))
        copy = os.path.join(tmp, "doc", os.path.basename(doc))
        for kind, name, subs, expect in cases:
            text = original
            for old, new in subs or [("`" + name + "`", "`gone`")]:
                text = text.replace(old, new)
            with open(copy, "w", encoding="utf-8") as f:
                f.write(text)
            fails, rc = run_checker(moraine, copy)
            pattern = re.compile(expect.replace("{n}", re.escape(name)))
            new = [l for l in fails if pattern.search(l) and l not in baseline]
            ok = rc != 0 and bool(new)
            failures += not ok
            print(f"{'ok  ' if ok else 'FAIL'} {kind} `{name}` removed: " +
                  (new[0] if ok else f"check_api_doc.py exit {rc} without a new FAIL line matching /{pattern.pattern}/"))
    print(f"{len(cases) - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
