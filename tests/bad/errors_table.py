#!/usr/bin/python3
"""moraine: the table of bad-input cases in doc/errors.md, kept in step with the tests.

Every case is a test that declares what it is and what the user must see:
  - tests/bad/NAME.lua (test bad.NAME), first lines
        -- expect: REGEX
        -- case: CATEGORY | DESCRIPTION
  - tests/robust/NAME.sh (test robust.NAME), header lines
        # case: CATEGORY | DESCRIPTION
        # expect: REGEX
    and the script prints "message: <what the user saw>".

  errors_table.py --write doc/errors.md MORAINE [PYTHON]
      runs every case and writes the table between the markers of the file,
      with the message each one printed;
  errors_table.py --check doc/errors.md
      (the test doc.errors_table) fails when a case has no row, a row has no
      case, a row's category or description differs from its case, or a row's
      message does not match its case's expect regex. The bad.* and robust.*
      tests check the same regexes against what moraine prints now, so the
      table cannot drift from the program.
"""
import glob
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BEGIN, END = "<!-- cases:begin -->", "<!-- cases:end -->"
ORDER = ["syntax", "keys", "types", "choices", "ranges", "geometry", "files", "runtime", "signals", "disk full",
         "permission", "warnings", "other"]


def cases():
    """[(test, category, description, expect_regex, path)] of every declared case"""
    found = []
    for path in sorted(glob.glob(os.path.join(HERE, "*.lua"))):
        head = open(path).read().split("\n")[:2]
        expect = re.match(r"-- expect: (.*)", head[0])
        if not expect:
            sys.exit(f"{path}: the first line must be '-- expect: REGEX'")
        name = os.path.basename(path)[:-4]
        case = re.match(r"-- case: (.*?) \| (.*)", head[1]) if len(head) > 1 else None
        # a deck without its '-- case:' line is still listed, under "other"
        category, description = case.groups() if case else ("other", name.replace("_", " "))
        found.append((f"bad.{name}", category, description, expect.group(1), path))
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "robust", "*.sh"))):
        text = open(path).read()
        case = re.search(r"^# case: (.*?) \| (.*)$", text, re.M)
        expect = re.search(r"^# expect: (.*)$", text, re.M)
        if case and expect:
            name = os.path.basename(path)[:-3]
            found.append((f"robust.{name}", case.group(1), case.group(2), expect.group(1), path))
    for test, category, *_ in found:
        if category not in ORDER:
            sys.exit(f"{test}: unknown category '{category}' (known: {', '.join(ORDER)})")
    found.sort(key=lambda c: (ORDER.index(c[1]), c[0]))
    return found


def normalise(message, outdir):
    """the message as any user would see it: no build or temporary directories"""
    message = re.sub(r"(?:/[^\s:'/]+)+/([\w.-]+\.lua):", r"\1:", message)
    return message.replace(outdir, "OUT")


def run_case(test, path, moraine, python, outdir):
    if test.startswith("bad."):
        proc = subprocess.run([os.path.join(HERE, "run.sh"), moraine, path, outdir], capture_output=True, text=True)
    else:
        proc = subprocess.run([path, moraine, outdir, python], capture_output=True, text=True)
    out = proc.stdout
    if proc.returncode != 0 or "\nmessage: " not in "\n" + out:
        sys.exit(f"{test} failed:\n{proc.stdout}{proc.stderr}")
    # what follows "message: " up to the pass/fail line; warnings may come
    # first, the error is the last line moraine printed
    said = ("\n" + out).split("\nmessage: ", 1)[1].split("\n")
    said = [l for l in said if l and not re.match(r"\d+ passed, \d+ failed", l)]
    errors = [l for l in said if l.startswith("moraine: ") and "warning [" not in l]
    message = (errors or said)[-1]
    if message.startswith("moraine: "):
        message = message[len("moraine: "):]
    return normalise(message, outdir)


def md_cell(text):
    return "`" + text.replace("|", "\\|") + "`"


def write(doc, moraine, python):
    rows = []
    with tempfile.TemporaryDirectory(prefix="moraine-errors-") as tmp:
        os.chmod(tmp, 0o755)  # robust.permission runs moraine as 'nobody' in there
        for i, (test, category, description, expect, path) in enumerate(cases(), 1):
            message = run_case(test, path, os.path.abspath(moraine), python, os.path.join(tmp, test))
            rows.append(f"| {i} | {category} | {description} | {test} | {md_cell(message)} |")
    table = "\n".join(["| # | kind | case | test | message |", "|---|---|---|---|---|"] + rows)
    text = open(doc).read()
    start, end = text.index(BEGIN) + len(BEGIN), text.index(END)
    open(doc, "w").write(text[:start] + "\n" + table + "\n" + text[end:])
    print(f"{doc}: {len(rows)} cases")


def check(doc):
    text = open(doc).read()
    body = text[text.index(BEGIN) + len(BEGIN):text.index(END)]
    rows = {}
    for line in body.strip().split("\n")[2:]:
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
        if len(cells) != 5:
            sys.exit(f"{doc}: a malformed row: {line}")
        _, category, description, test, message = cells
        rows[test] = (category, description, message.strip("`").replace("\\|", "|"))
    problems = []
    declared = cases()
    for test, category, description, expect, path in declared:
        if test not in rows:
            problems.append(f"{test} ({os.path.relpath(path, ROOT)}) has no row")
            continue
        row = rows.pop(test)
        if row[:2] != (category, description):
            problems.append(f"{test}: the row says '{row[0]} | {row[1]}', the test '{category} | {description}'")
        if not re.search(expect, row[2]):
            problems.append(f"{test}: the row's message does not match /{expect}/: {row[2]}")
    problems += [f"{test}: a row without a test" for test in rows]
    for p in problems:
        print("FAIL:", p)
    if problems:
        print("regenerate with: tests/bad/errors_table.py --write doc/errors.md BUILD/moraine")
    print(f"{len(declared)} cases, {len(problems)} problems")
    return not problems


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "--write":
        write(sys.argv[2], sys.argv[3], sys.argv[4] if len(sys.argv) > 4 else "/usr/bin/python3")
    elif len(sys.argv) == 3 and sys.argv[1] == "--check":
        sys.exit(0 if check(sys.argv[2]) else 1)
    else:
        sys.exit(__doc__)
