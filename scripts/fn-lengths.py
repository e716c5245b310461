#!/usr/bin/env python3
"""The longest functions of each crate, for before/after tables.

Usage:
    scripts/fn-lengths.py           # the 5 longest functions per crate
    scripts/fn-lengths.py -n 20     # the 20 longest
    scripts/fn-lengths.py --over 150   # every function over 150 lines, and whether its
                                       # file says why at its top (a comment naming the length)

A function's length is the lines from its `fn` keyword to its closing brace. Closures
and nested functions count inside their function (a nested `fn` is also listed alone).
Skipped: `tests/` folders, `#[cfg(test)]` items and `#[test]` functions; `fuzz/` is not a crate
of the workspace. Comments and string literals are removed before the braces are
matched. Python 3 standard library only.

JavaScript files (`.js` and `.mjs` under the crates' `src/` and under `js/`, without
`node_modules`) are listed too, under `== js`: every function body, named or not
(`function`, methods, arrow functions with a block), from its first line to its closing
brace, a nested function counting inside its enclosing one and listed alone too.
Anonymous ones are named `<anonymous>` or by the `const`/key they are assigned to.
"""

import argparse
import importlib.util
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))

# The cleaning functions of the import checker (comments, strings, #[cfg(test)] items).
_spec = importlib.util.spec_from_file_location("imports", os.path.join(HERE, "imports.py"))
imports = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(imports)

FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")
TEST_FN = re.compile(r"#\[test\]")


def functions(path):
    """(name, first line, line count) of every function body in `path`."""
    raw = open(path, encoding="utf-8").read()
    clean = imports.strip_test_items(imports.strip_strings(imports.strip_comments(raw)))
    # `#[test]` functions outside a test module
    for m in list(TEST_FN.finditer(clean)):
        brace = clean.find("{", m.end())
        if brace >= 0:
            end = imports.match_brace(clean, brace)
            clean = clean[: m.start()] + re.sub(r"[^\n]", " ", clean[m.start():end]) + clean[end:]
    out = []
    for m in FN.finditer(clean):
        # the body opens at the first `{` after the signature, unless a `;` ends a
        # declaration first (trait methods, extern functions)
        j, depth = m.end(), 0
        brace = -1
        while j < len(clean):
            ch = clean[j]
            if ch in "(<[":
                depth += 1
            elif ch in ")>]":
                depth -= 1
            elif ch == ";" and depth <= 0:
                break
            elif ch == "{" and depth <= 0:
                brace = j
                break
            j += 1
        if brace < 0:
            continue
        end = imports.match_brace(clean, brace)
        first = clean.count("\n", 0, m.start()) + 1
        last = clean.count("\n", 0, end - 1) + 1
        out.append((m.group(1), first, last - first + 1))
    return out


def says_why(path, lines):
    """Whether the file's top comment mentions a function of about `lines` lines or
    says why it is long (a heuristic for the `--over` listing)."""
    head = open(path, encoding="utf-8").read().split("\n")[:40]
    text = " ".join(l for l in head if l.lstrip().startswith("//"))
    return bool(re.search(r"\b(long|lines)\b", text))


def crate_files(crate_dir):
    src = os.path.join(crate_dir, "src")
    for root, dirs, files in os.walk(src):
        dirs[:] = sorted(d for d in dirs if d != "tests")
        for f in sorted(files):
            if f.endswith(".rs") and f != "test_support.rs":
                yield os.path.join(root, f)


JS_KEYWORDS = {"if", "for", "while", "switch", "catch", "function", "return", "with", "do", "else", "typeof", "await", "new", "yield", "delete", "void", "in", "of"}
JS_FN = re.compile(r"\bfunction\b\s*\*?\s*([A-Za-z_$][\w$]*)?\s*\(")
JS_METHOD = re.compile(r"(?:^|(?<=[\s,{;}]))(?:(?:async|static|get|set)\s+)*([A-Za-z_$][\w$]*)\s*\(")
JS_ARROW = re.compile(r"=>\s*\{")
JS_NAMED = re.compile(r"(?:\b(?:const|let|var)\s+([A-Za-z_$][\w$]*)\s*=|([A-Za-z_$][\w$]*)\s*:)\s*(?:async\s*)?[^=;{}]*$")


def js_clean(raw):
    """`raw` with comments and the insides of string, template and regex literals
    blanked (newlines kept). A `/` starts a regex where an operand is expected."""
    out, i, n = list(raw), 0, len(raw)

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    last = ""  # the last significant character before i
    while i < n:
        c = raw[i]
        if raw.startswith("//", i):
            j = raw.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
            i = j
        elif raw.startswith("/*", i):
            j = raw.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank(i, j)
            i = j
        elif c in "'\"`" or (c == "/" and (last == "" or last in "(,=:[!&|?{};+-*%<>~^")):
            j = i + 1
            in_class = False
            while j < n and (raw[j] != c or in_class):
                if raw[j] == "\\":
                    j += 1
                elif c == "/" and raw[j] == "[":
                    in_class = True
                elif c == "/" and raw[j] == "]":
                    in_class = False
                elif c != "`" and raw[j] == "\n":
                    break
                j += 1
            blank(i + 1, min(j, n))
            i = j + 1
            last = "a"
        else:
            if not c.isspace():
                last = c
            i += 1
    return "".join(out)


def js_functions(path):
    """(name, first line, line count) of every function body in the JavaScript file `path`."""
    clean = js_clean(open(path, encoding="utf-8").read())
    found = {}

    def body_after_params(open_paren):
        depth, j = 0, open_paren
        while j < len(clean):
            if clean[j] == "(":
                depth += 1
            elif clean[j] == ")":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        k = j + 1
        while k < len(clean) and clean[k].isspace():
            k += 1
        if clean.startswith("=>", k):
            m = JS_ARROW.match(clean, k)
            return m.end() - 1 if m else -1
        return k if k < len(clean) and clean[k] == "{" else -1

    def add(name, start, brace):
        if brace < 0 or brace in found:
            return
        end = imports.match_brace(clean, brace)
        first = clean.count("\n", 0, start) + 1
        last = clean.count("\n", 0, end - 1) + 1
        found[brace] = (name, first, last - first + 1)

    def assigned(pos):
        line = clean[clean.rfind("\n", 0, pos) + 1: pos]
        m = JS_NAMED.search(line)
        return (m.group(1) or m.group(2)) if m else "<anonymous>"

    for m in JS_FN.finditer(clean):
        add(m.group(1) or assigned(m.start()), m.start(), body_after_params(m.end() - 1))
    for m in JS_METHOD.finditer(clean):
        if m.group(1) not in JS_KEYWORDS:
            add(m.group(1), m.start(1), body_after_params(m.end() - 1))
    for m in JS_ARROW.finditer(clean):
        add(assigned(m.start()), m.start(), m.end() - 1)
    return sorted(found.values(), key=lambda r: r[1])


def js_files():
    """The JavaScript files of the crates' sources and of js/, links to them once."""
    seen = set()
    for top in [os.path.join(ROOT, "js"), os.path.join(ROOT, "crates")]:
        for root, dirs, files in os.walk(top):
            dirs[:] = sorted(d for d in dirs if d not in ("node_modules", "target", "tests", "test"))
            if top.endswith("crates") and os.sep + "src" not in root[len(top):]:
                continue
            for f in sorted(files):
                path = os.path.join(root, f)
                real = os.path.realpath(path)
                if f.endswith((".js", ".mjs")) and real not in seen:
                    seen.add(real)
                    yield path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-n", type=int, default=5, help="functions listed per crate (default 5)")
    ap.add_argument("--over", type=int, help="list every function longer than this many lines instead")
    args = ap.parse_args()
    base = os.path.join(ROOT, "crates")
    for crate in sorted(os.listdir(base)):
        found = []
        for f in crate_files(os.path.join(base, crate)):
            for name, line, count in functions(f):
                found.append((count, os.path.relpath(f, ROOT), line, name))
        print_section(crate, found, args)
    found = [(count, os.path.relpath(f, ROOT), line, name) for f in js_files() for name, line, count in js_functions(f)]
    print_section("js", found, args)


def print_section(title, found, args):
    """Prints one section: the longest functions (or those over `--over`, each with
    whether its file's top says why)."""
    found.sort(key=lambda x: (-x[0], x[1], x[2]))
    print(f"== {title}")
    rows = [r for r in found if r[0] > args.over] if args.over is not None else found[: args.n]
    for count, f, line, name in rows:
        note = ""
        if args.over is not None:
            note = "  (file top says why)" if says_why(os.path.join(ROOT, f), count) else "  (NO REASON AT FILE TOP)"
        print(f"  {count:5} {f}:{line} {name}{note}")


if __name__ == "__main__":
    main()
