#!/usr/bin/env python3
"""moraine: no function longer than a screen (run by ctest as check.function_length).

Fails when a function in src/ (C, bodies written inside a #define included)
or lua/ (`function ... end`) is longer than LIMIT lines, counted from the
line of its name to the line of its closing brace or `end`, and when a file
of FILE_LIMITS is longer than its limit.

There is no allow-list: a function over the limit is split.

    scripts/check_function_length.py [ROOT]      exit status 0 when it holds
"""
import os
import re
import sys

LIMIT = 80

# files that must exist and stay short as a whole: the reference
# form of the transfer kernels is there to be read beside the textbook
FILE_LIMITS = {"src/transfer/reference.c": 300}

C_KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "do", "else", "_Pragma", "__attribute__"}


C_BLANKED = re.compile(r"/\*.*?\*/|//[^\n]*|\"(?:\\.|[^\"\\\n])*\"|'(?:\\.|[^'\\\n])*'", re.S)


def blank_c(text):
    """text with comments, strings and character literals blanked (newlines kept)"""

    def blank(m):
        t = m.group()
        inner = re.sub(r"[^\n]", " ", t)
        return t[0] + inner[1:-1] + t[-1] if t[0] in "\"'" else inner

    return C_BLANKED.sub(blank, text)


def split_directives(text):
    """(code, macros): the code with every preprocessor directive blanked, and
    the body of each #define (continuation lines joined, newlines kept so that
    offsets still give line numbers) as (first line, text)"""
    lines = text.split("\n")
    code, macros, i = [], [], 0
    while i < len(lines):
        if re.match(r"\s*#", lines[i]):
            first = i
            body = [lines[i]]
            while lines[i].endswith("\\") and i + 1 < len(lines):
                i += 1
                body.append(lines[i])
            code.extend("" for _ in body)
            m = re.match(r"\s*#\s*define\s+\w+(\([^)]*\))?", body[0])
            if m:
                body[0] = " " * m.end() + body[0][m.end() :]
                macros.append((first, "\n".join(b[:-1] if b.endswith("\\") else b for b in body)))
        else:
            code.append(lines[i])
        i += 1
    return "\n".join(code), macros


def c_functions(code, first_line):
    """(name, first line, last line) of each function body at brace depth 0"""
    found, depth, stack = [], 0, []
    for m in re.finditer(r"[{}]", code):
        if m.group() == "{":
            if depth == 0:
                stack.append((m.start(), function_head(code, m.start())))
            depth += 1
        else:
            depth -= 1
            if depth == 0 and stack:
                _, head = stack.pop()
                if head:
                    name, at = head
                    line = first_line + code.count("\n", 0, at)
                    found.append((name, line, first_line + code.count("\n", 0, m.start())))
    return found


def function_head(code, brace):
    """(name, offset of the name) when the brace opens a function body"""
    i = brace - 1
    while i >= 0 and code[i].isspace():
        i -= 1
    if i < 0 or code[i] != ")":
        return None
    level = 0
    while i >= 0:  # back to the parameter list's opening parenthesis
        level += {")": 1, "(": -1}.get(code[i], 0)
        if level == 0:
            break
        i -= 1
    before = code[:i].rstrip()
    m = re.search(r"([A-Za-z_]\w*(?:\s*##\s*\w+)*)$", before)
    if m is None and before.endswith(")"):  # a name made by a macro: KNAME(p2g)
        j, level = len(before) - 1, 0
        while j >= 0:
            level += {")": 1, "(": -1}.get(before[j], 0)
            if level == 0:
                break
            j -= 1
        m2 = re.search(r"([A-Za-z_]\w*)\s*$", before[:j])
        if not m2:
            return None
        name, start = re.sub(r"\s+", "", before[m2.start(1) :]), m2.start(1)
    elif m:
        name, start = re.sub(r"\s+", "", m.group(1)), m.start(1)
    else:
        return None
    before = code[:start].rstrip()
    if name in C_KEYWORDS or before.endswith("=") or re.search(r"\b(struct|union|enum)$", before):
        return None
    return name, start


def scan_c(path):
    text = blank_c(open(path, encoding="utf-8").read())
    code, macros = split_directives(text)
    found = c_functions(code, 1)
    for first, body in macros:
        found += c_functions(body, first + 1)
    return found


LUA_TOKENS = re.compile(r"--\[(=*)\[.*?\]\1\]|--[^\n]*|\[(=*)\[.*?\]\2\]|\"(?:\\.|[^\"\\\n])*\"|'(?:\\.|[^'\\\n])*'"
                        r"|\b(function|if|do|repeat|end|until)\b", re.S)


def scan_lua(path):
    """(name, first line, last line) of each `function ... end`"""
    text = open(path, encoding="utf-8").read()
    found, stack = [], []
    for m in LUA_TOKENS.finditer(text):
        word = m.group(3)
        if not word:
            continue
        line = text.count("\n", 0, m.start()) + 1
        if word in ("function", "if", "do", "repeat"):
            stack.append((word, line, lua_name(text, m) if word == "function" else None))
        elif stack:
            word0, first, name = stack.pop()
            if word0 == "function":
                found.append((name, first, line))
    return found


def lua_name(text, m):
    after = re.match(r"\s*([\w.:]+)", text[m.end() :])
    if after:
        return after.group(1)
    before = re.search(r"([\w.]+|\[[^\]]*\])\s*=\s*$", text[: m.start()])
    return before.group(1) if before else "function@%d" % (text.count("\n", 0, m.start()) + 1)


def sources(root):
    for top, exts, scan in (("src", (".c", ".h"), scan_c), ("lua", (".lua",), scan_lua)):
        for d, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(exts):
                    path = os.path.join(d, f)
                    yield os.path.relpath(path, root), scan(path)


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    errors = []
    for rel, functions in sources(root):
        for name, first, last in functions:
            length = last - first + 1
            if length > LIMIT:
                errors.append("%s:%d: %s is %d lines (at most %d): split it" % (rel, first, name, length, LIMIT))
    for rel, limit in sorted(FILE_LIMITS.items()):
        path = os.path.join(root, rel)
        if not os.path.exists(path):
            errors.append("%s: missing" % rel)
            continue
        n = len(open(path, encoding="utf-8").read().splitlines())
        if n >= limit:
            errors.append("%s: %d lines (under %d)" % (rel, n, limit))
    for e in errors:
        print(e)
    print("check_function_length: %d problem(s), functions of at most %d lines" % (len(errors), LIMIT))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
