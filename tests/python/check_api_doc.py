#!/usr/bin/python3
"""moraine: check that the Lua API reference documents the whole API.

usage: check_api_doc.py MORAINE DOC
  MORAINE  the moraine executable (run with --list-options)
  DOC      doc/lua-api.md; the source tree is the directory above DOC's folder

What is checked, and the rule that makes an item count as documented.
Headings are Markdown ATX headings ("## ...", "### ...") outside fenced code
blocks; the *section* of a heading is its text up to the next heading of the
same or a higher level (so a "###" section includes its "####" subsections);
fenced code blocks are ignored everywhere. "`x`" means the exact code span x,
backticks included. A name is found in a heading when it appears inside one of
the heading's code spans, not preceded or followed by a letter, digit or "_".

1. Option groups and keys, from `MORAINE --list-options` (tab-separated lines:
   group, key, type, unit, doc). A group such as "simulation{} grid",
   "disk{} / sphere{}", "add_particles()" or "boundary face" names functions
   (the words ending in {} or (), brackets removed; when there is none, the
   first word) and optionally a nested table (the remaining words).
   - The group is documented when every function name is found in some
     heading; its sections are those headings' sections. A nested table of a
     function ("grid" in "simulation{} grid") must also be found in a heading
     inside them, and the group's sections narrow to those ("#### `grid`").
     For a group without a function word ("boundary face"), the remaining
     words only need to appear (as words, any case) in the sections.
   - A key is documented when "`key`" appears in one of its group's sections.
2. Every material model of the registry (src/material/material.c, names from
   src/material/*.c) has a heading naming `mpm.material.<model>`.
3. Every method of the simulation object (src/lua/lua_sim.c) has a heading
   naming `:<method>`; every region function (src/lua/lua_region.c) a heading
   naming `mpm.<function>` (`:contains` for the region method); every field
   of the module (src/lua/lua_module.c) and every helper defined in
   lua/moraine/init.lua a heading naming `mpm.<name>`; every function
   `M.<name>` of a library module lua/moraine/<module>.lua (other than
   init.lua) a heading naming `<module>.<name>`.
4. These names appear as "`name`" anywhere in the document: shape functions
   (src/shape/shape.c), transfer presets (src/transfer/scheme.c, with the
   FLIPX and NFLIPX patterns), stress updates (src/transfer/scheme.c),
   boundary kinds (src/grid/boundary.h and .c), particle output fields
   (src/io/particle_fields.c), diagnostics columns (src/solver/diagnostics.c),
   the simulation's metamethods (src/lua/lua_sim.c) and the command-line
   options (src/main.c).

A list that cannot be parsed from its source file counts as a failure, so a
refactoring that breaks a pattern here is noticed. Prints one line per
failure, then "N passed, M failed"; exits 0 when nothing failed, else 1.
"""
import os
import re
import subprocess
import sys

IDENT = r"[A-Za-z0-9_]"


class Doc:
    def __init__(self, path):
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        kept, in_fence = [], False
        for line in lines:
            if re.match(r"^\s*(```|~~~)", line):
                in_fence = not in_fence
                kept.append("")
                continue
            kept.append("" if in_fence else line)
        self.lines = kept
        self.text = "\n".join(kept)
        self.headings = []  # (level, text, first line, end line exclusive)
        for i, line in enumerate(kept):
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if m:
                self.headings.append([len(m.group(1)), m.group(2), i, len(kept)])
        for k, h in enumerate(self.headings):
            for later in self.headings[k + 1:]:
                if later[0] <= h[0]:
                    h[3] = later[2]
                    break

    def section(self, heading):
        return "\n".join(self.lines[heading[2]:heading[3]])

    @staticmethod
    def spans(text):
        return re.findall(r"`([^`]+)`", text)

    def headings_naming(self, pattern, within=None):
        """headings whose code spans match the regex `pattern`, optionally only
        those inside the line range of one of the headings in `within`"""
        found = []
        for h in self.headings:
            if within is not None and not any(w[2] <= h[2] < w[3] for w in within):
                continue
            if any(re.search(pattern, span) for span in self.spans(h[1])):
                found.append(h)
        return found

    def has_span(self, name, text=None):
        return "`" + name + "`" in (self.text if text is None else text)


def word(name):
    return r"(?<!" + IDENT + r")" + re.escape(name) + r"(?!" + IDENT + r")"


class Checker:
    def __init__(self):
        self.passed = 0
        self.failures = []

    def check(self, ok, what):
        if ok:
            self.passed += 1
        else:
            self.failures.append(what)
        return ok


def read(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8") as f:
        return f.read()


def strings_of_array(source, array):
    """the string literals of `... array[] = { ... };`"""
    m = re.search(re.escape(array) + r"\s*\[[^\]]*\]\s*=\s*\{(.*?)\};", source, re.S)
    return re.findall(r'"([^"]*)"', m.group(1)) if m else []


def block_of_array(source, array):
    m = re.search(re.escape(array) + r"\s*\[[^\]]*\]\s*=\s*\{(.*?)\};", source, re.S)
    return m.group(1) if m else ""


def source_lists(root):
    """name -> (list of names, source file) for the vocabulary checks"""
    lists = {}
    lists["shape function"] = (strings_of_array(read(root, "src/shape/shape.c"), "names"), "src/shape/shape.c")
    scheme = read(root, "src/transfer/scheme.c")
    presets = strings_of_array(scheme, "preset_names")
    lists["transfer preset"] = (presets, "src/transfer/scheme.c")
    lists["stress update"] = (strings_of_array(scheme, "stress_names"), "src/transfer/scheme.c")
    kinds = [k.lower() for k in re.findall(r"\bMRN_BC_([A-Z]+)\b", read(root, "src/grid/boundary.h"))
             if k != "KIND"]
    kinds += [k for k in strings_of_array(read(root, "src/grid/boundary.c"), "kind_names") if k not in kinds]
    lists["boundary kind"] = (list(dict.fromkeys(kinds)), "src/grid/boundary.h")
    fields = re.findall(r'\{\s*"(\w+)"\s*,\s*\d+\s*,\s*MRN_VTK_', read(root, "src/io/particle_fields.c"))
    lists["output field"] = (fields, "src/io/particle_fields.c")
    columns = re.findall(r'\{\s*"(\w+)"\s*,\s*"[^"]*"\s*\}',
                         block_of_array(read(root, "src/solver/diagnostics.c"), "columns"))
    lists["diagnostics column"] = (columns, "src/solver/diagnostics.c")
    sim = read(root, "src/lua/lua_sim.c")
    lists["metamethod"] = (re.findall(r'\{\s*"(__\w+)"\s*,', block_of_array(sim, "meta")), "src/lua/lua_sim.c")
    options = []  # the entries {"name", 'x' or 0, ...} of main.c's table
    for name, letter in re.findall(r'\{\s*"([\w-]+)"\s*,\s*(?:\'(\w)\'|0)\s*,', block_of_array(read(root, "src/main.c"), "options")):
        options += (["-" + letter] if letter else []) + ["--" + name]
    lists["command-line option"] = (options, "src/main.c")
    return lists


def heading_lists(root):
    """name -> (list of (label, heading regex), source file) for the heading checks"""
    lists = {}
    registry = re.findall(r"&mrn_material_(\w+)", block_of_array(read(root, "src/material/material.c"), "registry"))
    models = []
    mdir = os.path.join(root, "src/material")
    model_sources = "".join(read(root, os.path.join("src/material", f)) for f in sorted(os.listdir(mdir))
                            if f.endswith(".c"))
    for sym in registry:
        m = re.search(r"mrn_material_type\s+mrn_material_" + re.escape(sym) + r"\s*=\s*\{.*?\.name\s*=\s*\"(\w+)\"",
                      model_sources, re.S)
        if m:
            models.append(m.group(1))
        else:
            models.append(None)
    lists["material model"] = ([(f"mpm.material.{m}" if m else f"(no .name for mrn_material_{s})",
                                 word(f"material.{m}") if m else r"(?!)") for m, s in zip(models, registry)],
                               "src/material/material.c")
    sim = read(root, "src/lua/lua_sim.c")
    methods = re.findall(r'\{\s*"(\w+)"\s*,\s*l_\w+\s*\}', block_of_array(sim, "methods"))
    lists["simulation method"] = ([(f"sim:{m}", r":" + re.escape(m) + r"(?!" + IDENT + ")") for m in methods],
                                  "src/lua/lua_sim.c")
    region = read(root, "src/lua/lua_region.c")
    fns = re.findall(r'\{\s*"(\w+)"\s*,\s*l_\w+\s*\}', block_of_array(region, "fns"))
    fns += re.findall(r'lua_pushcclosure\(L,\s*l_\w+,\s*\d+\);\s*lua_setfield\(L,\s*-2,\s*"(\w+)"\)', region)
    entries = [(f"mpm.{f}", r"mpm\." + re.escape(f) + r"(?!" + IDENT + ")") for f in fns]
    for m in re.findall(r'lua_pushcfunction\(L,\s*l_\w+\);\s*lua_setfield\(L,\s*-2,\s*"(\w+)"\)', region):
        entries.append((f"region:{m}", r":" + re.escape(m) + r"(?!" + IDENT + ")"))
    lists["region function"] = (entries, "src/lua/lua_region.c")
    module = read(root, "src/lua/lua_module.c")
    names = re.findall(r'lua_setfield\(L,\s*module,\s*"(\w+)"\)', module)
    names += re.findall(r'lua_setfield\(L,\s*-2,\s*"(deck\w*)"\)', module)
    lists["module field"] = ([(f"mpm.{n}", r"mpm\." + re.escape(n) + r"(?![\w.])") for n in names],
                             "src/lua/lua_module.c")
    helpers = re.findall(r"^\s*function\s+(mpm(?:\.\w+)+)\s*\(", read(root, "lua/moraine/init.lua"), re.M)
    lists["Lua helper"] = ([(h, re.escape(h) + r"(?![\w.])") for h in helpers], "lua/moraine/init.lua")
    functions = []
    for f in sorted(os.listdir(os.path.join(root, "lua/moraine"))):
        if f.endswith(".lua") and f != "init.lua":
            module = f[:-len(".lua")]
            for fn in re.findall(r"^function\s+M\.(\w+)\s*\(", read(root, "lua/moraine/" + f), re.M):
                name = f"{module}.{fn}"
                functions.append((name, r"(?<![\w.])" + re.escape(name) + r"(?![\w.])"))
    lists["Lua library function"] = (functions, "lua/moraine/*.lua")
    return lists


def list_options(moraine):
    r = subprocess.run([moraine, "--list-options"], capture_output=True, text=True, timeout=60)
    if r.returncode != 0:
        raise RuntimeError(f"{moraine} --list-options exited with {r.returncode}: {r.stderr.strip()}")
    groups = {}
    for line in r.stdout.splitlines():
        if not line.strip():
            continue
        parts = line.split("\t")
        if len(parts) != 5:
            raise RuntimeError(f"--list-options: expected 5 tab-separated fields, got: {line!r}")
        groups.setdefault(parts[0], []).append(parts[1])
    return groups


def has_function_word(group):
    return any(w.endswith("{}") or w.endswith("()") for w in group.split())


def split_group(group):
    words = group.split()
    funcs = [w[:-2] for w in words if w.endswith("{}") or w.endswith("()")]
    if funcs:
        nested = [w for w in words if not (w.endswith("{}") or w.endswith("()")) and w != "/"]
    else:
        funcs, nested = words[:1], [w for w in words[1:] if w != "/"]
    return funcs, nested


def check_groups(doc, checker, groups):
    for group, keys in groups.items():
        funcs, nested = split_group(group)
        sections = []
        missing = []
        for f in funcs:
            found = doc.headings_naming(word(f))
            if not found:
                missing.append(f)
            sections += found
        problem = f"no heading names {', '.join(missing)}" if missing else None
        if not problem and nested and has_function_word(group):
            for n in nested:
                narrowed = doc.headings_naming(word(n), within=sections)
                if not narrowed:
                    problem = f"no heading inside the section of {', '.join(funcs)} names {n}"
                    break
                sections = narrowed
        text = "\n".join(doc.section(h) for h in sections)
        if not problem and not all(re.search(word(n), text, re.I) for n in nested):
            problem = f"its section does not mention {' '.join(nested)}"
        ok = checker.check(problem is None, f"group '{group}': {problem}")
        for key in keys:
            checker.check(ok and doc.has_span(key, text),
                          f"group '{group}': key `{key}` is not documented in its section"
                          + ("" if ok else " (the group itself is not documented)"))


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    moraine, doc_path = argv[1], argv[2]
    root = os.path.dirname(os.path.dirname(os.path.abspath(doc_path)))
    checker = Checker()
    try:
        doc = Doc(doc_path)
    except OSError as e:
        print(f"FAIL: cannot read {doc_path}: {e}")
        print("0 passed, 1 failed")
        return 1

    try:
        groups = list_options(moraine)
        checker.check(bool(groups), f"{moraine} --list-options printed no option")
        check_groups(doc, checker, groups)
    except (OSError, RuntimeError, subprocess.SubprocessError) as e:
        checker.check(False, f"cannot get the options: {e}")

    try:
        for what, (entries, source) in heading_lists(root).items():
            if checker.check(bool(entries), f"no {what} found in {source} (has its format changed?)"):
                for label, pattern in entries:
                    checker.check(bool(doc.headings_naming(pattern)), f"{what} {label} ({source}) has no heading")
        for what, (names, source) in source_lists(root).items():
            if checker.check(bool(names), f"no {what} found in {source} (has its format changed?)"):
                for name in names:
                    checker.check(doc.has_span(name), f"{what} `{name}` ({source}) is not mentioned")
                if what == "transfer preset":
                    for pattern in ("FLIPX", "NFLIPX"):
                        if pattern not in names:
                            checker.check(doc.has_span(pattern), f"{what} `{pattern}` is not mentioned")
    except OSError as e:
        checker.check(False, f"cannot read the sources under {root}: {e}")

    for failure in checker.failures:
        print("FAIL: " + failure)
    print(f"{checker.passed} passed, {len(checker.failures)} failed")
    return 1 if checker.failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
