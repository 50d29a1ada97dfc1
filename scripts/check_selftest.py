#!/usr/bin/env python3
"""moraine: the source checks notice what they are for (run by ctest as check.selftest).

Copies src/ and lua/ into a temporary tree, breaks one rule at a time and
requires check_layers.py and check_function_length.py to fail on it with
the file and the reason, and to pass on the untouched copy.

    scripts/check_selftest.py [ROOT]
"""
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def run(script, root):
    p = subprocess.run([sys.executable, os.path.join(HERE, script), root], capture_output=True, text=True)
    return p.returncode, p.stdout


def append(path, text):
    with open(path, "a", encoding="utf-8") as f:
        f.write(text)


def long_c(name, lines, in_macro):
    cont = " \\" if in_macro else ""
    head = "#define MAKE_%s(x)%s\n" % (name, cont) if in_macro else ""
    body = "".join("  n += %d; /* } */%s\n" % (i, cont) for i in range(lines))
    return "\n%sstatic int %s(int n) {%s\n%s  return n;%s\n}\n" % (head, name, cont, body, cont)


CASES = [
    # (what, script, change(tree), text the report must hold)
    ("an include upwards", "check_layers.py",
     lambda t: append(os.path.join(t, "src/core/log.c"), '\n#include "io/output.h"\n'),
     "src/core/log.c:"),
    ("a long C function", "check_function_length.py",
     lambda t: append(os.path.join(t, "src/core/log.c"), long_c("too_long", 85, False)),
     "too_long is"),
    ("a long function in a macro", "check_function_length.py",
     lambda t: append(os.path.join(t, "src/core/log.c"), long_c("in_macro", 85, True)),
     "in_macro is"),
    ("a long Lua function", "check_function_length.py",
     lambda t: append(os.path.join(t, "lua/moraine/geometry.lua"),
                      "\nlocal function too_long(x)\n" + "  if x then x = x + 1 end -- end\n" * 85 + "  return x\nend\n"),
     "too_long is"),
    ("a long reference form", "check_function_length.py",
     lambda t: append(os.path.join(t, "src/transfer/reference.c"), "/* line */\n" * 300),
     "src/transfer/reference.c:"),
]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, ".."))
    failures = 0
    with tempfile.TemporaryDirectory(prefix="moraine-checks-") as tmp:
        for what, script, change, expect in [("the tree as it is", s, None, None)
                                             for s in ("check_layers.py", "check_function_length.py")] + CASES:
            tree = os.path.join(tmp, "tree")
            shutil.rmtree(tree, ignore_errors=True)
            for top in ("src", "lua"):
                shutil.copytree(os.path.join(root, top), os.path.join(tree, top))
            if change:
                change(tree)
            rc, out = run(script, tree)
            ok = rc == 0 if change is None else rc != 0 and expect in out
            print("%s: %s %s" % ("ok" if ok else "FAIL", script, what))
            if not ok:
                print(out)
                failures += 1
    print("check_selftest: %d failure(s)" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
