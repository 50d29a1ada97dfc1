#!/usr/bin/env python3
"""moraine: the modules of src/ depend one way (run by ctest as check.layers).

Every `#include "module/file.h"` in src/ is read. A module may include its
own headers and those of the modules below it in ORDER; src/main.c stands
above them all. The check fails on an include from a module into one above
it, and on a cycle among the modules (which ORDER rules out as long as it
is a plain list: the cycle check guards the day it is not).

    scripts/check_layers.py [ROOT]      exit status 0 when the layers hold
"""
import os
import re
import sys

ORDER = ["core", "shape", "grid", "particles", "transfer", "material", "solver", "implicit", "io", "lua"]


INCLUDE = re.compile(r'^\s*#\s*include\s*"([A-Za-z_]\w*)/([^"]+)"')


def includes(root):
    """(file, line number, including module, included module, header)"""
    src = os.path.join(root, "src")
    for d, dirs, files in os.walk(src):
        dirs.sort()
        for f in sorted(files):
            if not f.endswith((".c", ".h")):
                continue
            path = os.path.join(d, f)
            rel = os.path.relpath(path, root)
            parts = os.path.relpath(path, src).split(os.sep)
            module = parts[0] if len(parts) > 1 else None  # None: src/main.c, above every module
            with open(path, encoding="utf-8") as fh:
                for n, line in enumerate(fh, 1):
                    m = INCLUDE.match(line)
                    if m:
                        yield rel, n, module, m.group(1), m.group(1) + "/" + m.group(2)


def find_cycle(edges):
    """a list of modules that depend on one another in a circle, or None"""
    graph = {}
    for a, b in edges:
        graph.setdefault(a, set()).add(b)
    state, path = {}, []

    def visit(a):
        state[a] = 1
        path.append(a)
        for b in sorted(graph.get(a, ())):
            if state.get(b) == 1:
                return path[path.index(b) :] + [b]
            if b not in state:
                cycle = visit(b)
                if cycle:
                    return cycle
        state[a] = 2
        path.pop()
        return None

    for a in sorted(graph):
        if a not in state:
            cycle = visit(a)
            if cycle:
                return cycle
    return None


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    rank = {m: i for i, m in enumerate(ORDER)}
    errors, edges = [], set()
    for rel, n, module, target, header in includes(root):
        if target not in rank:
            errors.append("%s:%d: includes %s of '%s', which is not a module of the list in %s" %
                          (rel, n, header, target, os.path.basename(__file__)))
            continue
        if module is None or module == target:
            continue
        if module not in rank:
            errors.append("%s:%d: src/%s/ is not a module of the list in %s" %
                          (rel, n, module, os.path.basename(__file__)))
            continue
        edges.add((module, target))
        if rank[target] > rank[module]:
            errors.append("%s:%d: %s/ includes %s from %s/, a module above it (%s)" %
                          (rel, n, module, header, target, " -> ".join(ORDER)))
    cycle = find_cycle(edges)
    if cycle:
        errors.append("module cycle: " + " -> ".join(cycle))
    for e in errors:
        print(e)
    print("check_layers: %d problem(s)" % len(errors))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
