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
        found.sort(key=lambda x: (-x[0], x[1], x[2]))
        print(f"== {crate}")
        rows = [r for r in found if r[0] > args.over] if args.over is not None else found[: args.n]
        for count, f, line, name in rows:
            note = ""
            if args.over is not None:
                note = "  (file top says why)" if says_why(os.path.join(ROOT, f), count) else "  (NO REASON AT FILE TOP)"
            print(f"  {count:5} {f}:{line} {name}{note}")


if __name__ == "__main__":
    main()
