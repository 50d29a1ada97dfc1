#!/usr/bin/env python3
"""Compare two directories of moraine checkpoints object by object.

Every dataset's bytes, every attribute's value and the set of objects must
be the same; only the attributes that name the program that wrote the file
(moraine_version) may differ, and the /resume group (what a resumed run
continues: output settings and file positions, not the simulation's state)
may be present on one side only. Exit status 0 when all files agree, 1 otherwise.

    compare.py DIR_A DIR_B
"""
import os
import sys

import h5py
import numpy as np

IGNORED_ATTRS = {"moraine_version"}
IGNORED_GROUPS = ("resume",)


def objects(f):
    names = []
    f.visit(names.append)
    return ["/"] + sorted(n for n in names if n.split("/")[0] not in IGNORED_GROUPS)


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def compare_file(pa, pb):
    diffs = []
    with h5py.File(pa, "r") as fa, h5py.File(pb, "r") as fb:
        na, nb = objects(fa), objects(fb)
        if na != nb:
            diffs.append("objects differ: only in A %s, only in B %s" %
                         (sorted(set(na) - set(nb)), sorted(set(nb) - set(na))))
        for name in (n for n in na if n in set(nb)):
            oa, ob = fa[name], fb[name]
            if isinstance(oa, h5py.Dataset) != isinstance(ob, h5py.Dataset):
                diffs.append("%s: dataset in one file, group in the other" % name)
                continue
            if isinstance(oa, h5py.Dataset) and not same_value(oa[()], ob[()]):
                diffs.append("%s: data differ" % name)
            ka = set(oa.attrs) - IGNORED_ATTRS
            kb = set(ob.attrs) - IGNORED_ATTRS
            if ka != kb:
                diffs.append("%s: attributes differ: %s vs %s" % (name, sorted(ka), sorted(kb)))
            for k in sorted(ka & kb):
                if not same_value(oa.attrs[k], ob.attrs[k]):
                    diffs.append("%s@%s: %r vs %r" % (name, k, oa.attrs[k], ob.attrs[k]))
    return diffs


def main(a, b):
    fa = sorted(f for f in os.listdir(a) if f.endswith(".h5"))
    fb = sorted(f for f in os.listdir(b) if f.endswith(".h5"))
    bad = 0
    if fa != fb:
        print("file lists differ: only in %s %s, only in %s %s" %
              (a, sorted(set(fa) - set(fb)), b, sorted(set(fb) - set(fa))))
        bad += 1
    for name in sorted(set(fa) & set(fb)):
        diffs = compare_file(os.path.join(a, name), os.path.join(b, name))
        if diffs:
            bad += 1
            print("%s: %d difference(s)" % (name, len(diffs)))
            for d in diffs[:8]:
                print("   " + d)
    print("%d checkpoint(s) compared, %d differ" % (len(set(fa) & set(fb)), bad))
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
