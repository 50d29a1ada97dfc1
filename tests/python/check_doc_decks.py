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
example of it).

What the documentation says a deck printed or wrote is checked against the
run of the last deck block before it, so its figures cannot go stale:

  ```text output      what the run printed: the lines, in order, of the
                      run's log.txt (everything printed, thermo lines and
                      summary included). A line "..." skips any number of
                      lines; other lines follow each other. Numbers agree to
                      1e-4 of their size, to their last printed digit, or to
                      1e-6 of the line's largest number (round-off noise).
  ```text files       a listing of the output directory: the first line the
                      directory, then one entry a line, "NAME  description";
                      "A ... B" stands for the numbered files from A to B, a
                      name ending in "/" for a directory. The entries must be
                      exactly the files and directories there.
  ```text header F    the first line of the file F the run wrote.
  column N is `NAME`  (in the text) NAME is column N of the last header
                      checked; every awk field $M (M > 2) of the next code
                      block is then $N.

Prints one line per block, then "N passed, M failed"; exits 0 when nothing
failed.
"""
import os
import re
import shutil
import subprocess
import sys
import time

TIMEOUT = 120  # s per block; the marked blocks take a few seconds each
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*(.*?)\s*$")


CLAIM = re.compile(r"column (\d+) is `(\w+)`")


def deck_blocks(path):
    """[(first line number, --set arguments, code, [checks])] of the deck blocks of a
    Markdown file; a check is (line number, kind, argument, text) of a block or claim
    that follows the deck"""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    blocks, i, claim = [], 0, None
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            for c in CLAIM.finditer(lines[i]):
                claim = (i + 1, int(c.group(1)), c.group(2))
                if blocks:
                    blocks[-1][3].append((i + 1, "claim", claim, ""))
            i += 1
            continue
        fence, info = m.group(2), m.group(3).split()
        end = i + 1
        while end < len(lines) and not lines[end].strip().startswith(fence):
            end += 1
        text = "\n".join(lines[i + 1:end])
        if len(info) >= 2 and info[0] == "lua" and info[1] == "deck":
            sets = info[2:]
            bad = [w for w in sets if "=" not in w]
            if bad:
                raise ValueError(f"{path}:{i + 1}: fence words {bad} are not NAME=VALUE")
            blocks.append((i + 1, sets, text + "\n", []))
        elif len(info) >= 2 and info[0] == "text" and info[1] in ("output", "files", "header"):
            if not blocks:
                raise ValueError(f"{path}:{i + 1}: a ```text {info[1]} block before any deck block")
            blocks[-1][3].append((i + 1, info[1], info[2] if len(info) > 2 else "", text))
        elif claim and blocks:
            blocks[-1][3].append((i + 1, "awk", claim, text))
        claim = None if m else claim
        i = end + 1
    return blocks


# ---- what the documentation says the run printed and wrote ---------------------

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def last_digit(text):
    """the value of one unit in the last printed digit of a number"""
    mant, _, exp = text.lower().partition("e")
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 10.0 ** (int(exp or 0) - decimals)


def same_line(doc, run):
    """'' when the run's line says what the documentation's does, else why not"""
    dn, rn = NUMBER.findall(doc), NUMBER.findall(run)
    if NUMBER.sub("#", doc).split() != NUMBER.sub("#", run).split() or len(dn) != len(rn):
        return "differs"
    scale = max([abs(float(x)) for x in rn] + [0.0])
    for d, r in zip(dn, rn):
        tol = max(1e-4 * abs(float(r)), last_digit(d), 1e-6 * scale)
        if abs(float(d) - float(r)) > tol:
            return f"{d} is {r} now"
    return ""


def check_output(text, log):
    """'' when the lines of `text` are lines of the log, in order, else why not"""
    want = text.split("\n")
    have = log.rstrip("\n").split("\n")
    pos, gap = 0, True  # the first line may come anywhere
    for line in want:
        if line.strip() == "...":
            gap = True
            continue
        candidates = range(pos, len(have)) if gap else range(pos, min(pos + 1, len(have)))
        found = next((k for k in candidates if not same_line(line, have[k])), None)
        if found is None:
            # the line the doc most likely means: of the same words, the most numbers alike
            words = NUMBER.sub("#", line).split()
            alike = [have[k] for k in candidates if NUMBER.sub("#", have[k]).split() == words]
            near = max(alike, key=lambda h: sum(a == b for a, b in zip(NUMBER.findall(h), NUMBER.findall(line))),
                       default=None)
            if near is None:
                return f"printed {line.strip()!r}: no such line in the run's log (in order)"
            return f"printed {line.strip()!r}: the run printed {near.strip()!r} ({same_line(line, near)})"
        pos, gap = found + 1, False
    return ""


def expand(entry):
    """the names of a listing entry: "a_000000.vtp ... a_000003.vtp" -> 4 names"""
    m = re.match(r"(\S*?)(\d+)(\S*) \.\.\. (\S*?)(\d+)(\S*)$", entry)
    if not m:
        return [entry]
    head, first, tail, _, last, _ = m.groups()
    return [f"{head}{k:0{len(first)}d}{tail}" for k in range(int(first), int(last) + 1)]


def check_files(text, outdir):
    lines = [l for l in text.split("\n") if l.strip()]
    listed = set()
    for line in lines[1:]:
        entry = re.split(r"\s{2,}", line.strip())[0]
        listed.update(expand(entry))
    there = {n for n in os.listdir(outdir) if not n.startswith(".")}  # hidden: not the deck's
    there = {n + "/" if os.path.isdir(os.path.join(outdir, n)) else n for n in there}
    missing, unlisted = sorted(listed - there), sorted(there - listed)
    return f"listed but not written: {missing}; written but not listed: {unlisted}" if missing or unlisted else ""


def check_after(checks, outdir, state):
    """[(line, kind, why not or '')] of the checks of one deck's run (state: the last header checked)"""
    results = []
    log_path = os.path.join(outdir, "log.txt")
    log = open(log_path, encoding="utf-8").read() if os.path.exists(log_path) else ""
    for line, kind, arg, text in checks:
        why = ""
        if kind == "output":
            why = check_output(text, log)
        elif kind == "files":
            why = check_files(text, outdir)
        elif kind == "header":
            path = os.path.join(outdir, arg)
            first = open(path).readline().rstrip("\n") if os.path.exists(path) else f"({arg} not written)"
            state["header"] = first.split(",")
            why = "" if first == text.strip() else f"the run wrote {first!r}"
        elif kind == "claim":
            _, n, name = arg
            cols = state.get("header", [])
            there = cols[n - 1] if n <= len(cols) else "absent"
            why = "" if there == name else f"column {n} is {there!r}"
        elif kind == "awk":
            used = {int(k) for k in re.findall(r"\$(\d+)", text) if int(k) > 2}
            why = "" if used <= {arg[1]} else f"the code uses columns {sorted(used)}, the text says {arg[1]}"
        results.append((line, kind, why))
    return results


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
        state = {}
        for line, sets, code, checks in blocks:
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
                continue
            for at, kind, why in check_after(checks, os.path.join(outdir, name), state):
                if why:
                    failed.append(f"{doc}:{at}: {kind}: {why}")
                    print(f"FAIL {doc}:{at}: {kind}: {why}")
                else:
                    passed += 1
                    print(f"ok   {doc}:{at} ({kind})")
    print(f"{passed} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
