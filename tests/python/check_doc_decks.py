#!/usr/bin/python3
"""moraine: run the decks of the documentation, so that its examples cannot rot.

usage: check_doc_decks.py MORAINE OUTDIR DOC.md [DOC.md ...]

A code block is a deck when its fence's info string is "lua deck", optionally
followed by NAME=VALUE words that are passed as `--set NAME=VALUE` (to shorten
a run that reads mpm.param):

    ```lua deck
    local sim = mpm.simulation{ ... }
    ```

Each deck block is written to OUTDIR/<doc>_L<line>.lua and run as
`MORAINE block.lua -q -o OUTDIR/<doc>_L<line>` (so files it writes land there);
it passes when moraine exits 0 within TIMEOUT seconds. A document without any
deck block fails too (a marker removed by mistake would otherwise hide every
example of it). Prints one line per block, then "N passed, M failed"; exits 0
when nothing failed.
"""
import os
import re
import shutil
import subprocess
import sys
import time

TIMEOUT = 120  # s per block; the marked blocks take a few seconds each
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*(.*?)\s*$")


def deck_blocks(path):
    """[(first line number, --set arguments, code)] of the deck blocks of a Markdown file"""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, info = m.group(2), m.group(3).split()
        end = i + 1
        while end < len(lines) and not lines[end].strip().startswith(fence):
            end += 1
        if len(info) >= 2 and info[0] == "lua" and info[1] == "deck":
            sets = info[2:]
            bad = [w for w in sets if "=" not in w]
            if bad:
                raise ValueError(f"{path}:{i + 1}: fence words {bad} are not NAME=VALUE")
            blocks.append((i + 1, sets, "\n".join(lines[i + 1:end]) + "\n"))
        i = end + 1
    return blocks


def main(argv):
    if len(argv) < 4:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    moraine, outdir, docs = os.path.abspath(argv[1]), os.path.abspath(argv[2]), argv[3:]
    os.makedirs(outdir, exist_ok=True)
    passed, failed = 0, []
    for doc in docs:
        stem = os.path.splitext(os.path.basename(doc))[0]
        try:
            blocks = deck_blocks(doc)
        except (OSError, ValueError) as e:
            failed.append(str(e))
            print(f"FAIL {e}")
            continue
        if not blocks:
            failed.append(f"{doc}: no ```lua deck block")
            print(f"FAIL {doc}: no ```lua deck block")
            continue
        for line, sets, code in blocks:
            name = f"{stem}_L{line}"
            deck = os.path.join(outdir, name + ".lua")
            with open(deck, "w", encoding="utf-8") as f:
                f.write(code)
            shutil.rmtree(os.path.join(outdir, name), ignore_errors=True)  # a fresh directory: no earlier run's outputs
            cmd = [moraine, deck, "-q", "-o", os.path.join(outdir, name)]
            for s in sets:
                cmd += ["--set", s]
            start = time.monotonic()
            try:
                r = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT)
                ok, why = r.returncode == 0, f"exit {r.returncode}: {(r.stderr or r.stdout).strip()[-600:]}"
            except subprocess.TimeoutExpired:
                ok, why = False, f"still running after {TIMEOUT} s"
            where = f"{doc}:{line}"
            if ok:
                passed += 1
                print(f"ok   {where} ({time.monotonic() - start:.1f} s)")
            else:
                failed.append(f"{where}: {why}")
                print(f"FAIL {where}: {why}")
    print(f"{passed} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
