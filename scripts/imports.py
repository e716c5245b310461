#!/usr/bin/env python3
"""Module imports of every crate of the workspace, import circles, and the library's layers.

Usage:
    scripts/imports.py            # per crate: each file and the files it imports, then findings
    scripts/imports.py --summary  # findings only (circles, upward imports, root re-exports)
    scripts/imports.py --check    # findings only; exit 1 on a circle, an upward import or a use through the root
    scripts/imports.py --crate stripkit-cli   # one crate

What counts as an import of file B by file A: a `use` (also `pub use`) or an inline path
(`crate::a::b`, `super::x`, `self::x`, or `child::x` for a module declared in A) that
names B's module or an item B defines. Names re-exported by a `mod.rs`/`lib.rs`
(`pub use x::{Name}`) are followed to the file that defines them, so importing
`crate::Mesh` counts as importing `mesh/mod.rs`'s definition, not `lib.rs`.
`#[cfg(test)]` items (test modules and test-only functions) and `tests/` are skipped.
A parent declaring a child (`mod x;`) is not an import. A module using its own
submodules (`mod.rs` -> `mod.rs/child.rs`, `main.rs` -> every module) runs down by
construction, so circles are searched without those edges (`--strict` keeps them):
a child may use what its parent defines, and siblings may not import each other both ways.

Findings:
  * circles: strongly connected components of the file graph with more than one file;
  * upward imports (library only): a file whose top-level module sits lower in LAYERS
    than the module of a file it imports;
  * root re-exports (library only): `use crate::Name` where `Name` is an item that
    `lib.rs` re-exports (a module imports from the module that defines the name, so
    that lib.rs stays the top of the layers).

Python 3 standard library only. The parser is a careful approximation of Rust's module
rules (comments and string literals removed, `#[path]` honoured, uniform paths); it is
meant for this workspace, not for every Rust crate.
"""

import argparse
import os
import re
import sys

# The library's top-level modules, bottom to top. A module may import its own layer and
# those below; an entry "a+b" is one layer of two modules. `lib` is the crate root.
LAYERS = [
    "error",
    "vec3",
    "hint",  # processor hints (prefetch) that change no result
    "parallel",  # thread counts and the ordered map: used by every layer that splits work
    "strip",  # index sequences only: no Mesh, so files can carry strips
    "mesh",  # mesh/ and mesh/io/: files to and from Mesh (and StripSet, for PLY tristrips)
    "metrics",
    "topology",
    "matching",
    "stripify+improve",
    "pipeline",  # the door
    "vertex_order",
    "scene+assets",  # stripping a glTF scene, above the door
    "cull",
    "distance",  # surface distances; simplify measures its error with them
    "simplify",
    "lod",
    "gen",
    "test_support+tests",
    "lib",
]

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def layer_index():
    index = {}
    for i, entry in enumerate(LAYERS):
        for name in entry.split("+"):
            index[name] = i
    return index


# ---------------------------------------------------------------- source cleaning


def strip_comments(src):
    """`src` with comments replaced by spaces (newlines kept); strings left in place."""
    out = []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif src.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", src[i:j]))
            i = j
        elif c == '"' or (c == "r" and re.match(r'r#*"', src[i:i + 10]) and not (i and (src[i - 1].isalnum() or src[i - 1] == "_"))):
            j = skip_string(src, i)
            out.append(src[i:j])
            i = j
        elif c == "'":
            j = skip_char(src, i)
            out.append(src[i:j])
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def skip_string(src, i):
    """The index after the string literal starting at `i` (plain or raw)."""
    if src[i] == "r":
        m = re.match(r'r(#*)"', src[i:])
        close = '"' + m.group(1)
        j = src.find(close, i + len(m.group(0)))
        return len(src) if j < 0 else j + len(close)
    j = i + 1
    while j < len(src):
        if src[j] == "\\":
            j += 2
        elif src[j] == '"':
            return j + 1
        else:
            j += 1
    return j


def skip_char(src, i):
    """The index after a char literal at `i`, or after the quote of a lifetime."""
    m = re.match(r"'(\\.[^']*|[^\\'])'", src[i:])
    return i + len(m.group(0)) if m else i + 1


def strip_strings(src):
    """`src` (comments already removed) with string and char literals blanked."""
    out = []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if c == '"' or (c == "r" and re.match(r'r#*"', src[i:i + 10]) and not (i and (src[i - 1].isalnum() or src[i - 1] == "_"))):
            j = skip_string(src, i)
            out.append('""' + re.sub(r"[^\n]", " ", src[i + 2:j]) if j - i >= 2 else src[i:j])
            i = j
        elif c == "'":
            j = skip_char(src, i)
            out.append(re.sub(r"[^\n]", " ", src[i:j]) if j - i > 1 else "'")
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def match_brace(src, i):
    """Index after the block whose `{` is at `i`."""
    depth = 0
    for j in range(i, len(src)):
        if src[j] == "{":
            depth += 1
        elif src[j] == "}":
            depth -= 1
            if depth == 0:
                return j + 1
    return len(src)


TEST_ATTR = re.compile(r"#\[cfg\((test|doctest|all\(test[^\]]*|any\(test[^\]]*)\)\]")


def strip_test_items(src):
    """`src` (comments and strings blanked) without `#[cfg(test)]` items."""
    while True:
        m = TEST_ATTR.search(src)
        if not m:
            return src
        j = m.end()
        # the item: up to `;` or through its first block, whichever comes first
        semi = src.find(";", j)
        brace = src.find("{", j)
        if brace < 0 or (0 <= semi < brace):
            end = len(src) if semi < 0 else semi + 1
        else:
            end = match_brace(src, brace)
        src = src[: m.start()] + re.sub(r"[^\n]", " ", src[m.start():end]) + src[end:]


# ---------------------------------------------------------------- module tree


class Module:
    def __init__(self, path, file, inline=False):
        self.path = path  # tuple of names from the crate root
        self.file = file  # the file that holds its items
        self.inline = inline
        self.children = {}  # name -> Module
        self.reexports = {}  # name -> absolute path (tuple) it names
        self.globs = []  # absolute module paths re-exported with `*`
        self.items = set()  # names defined here (fn, struct, enum, ...)
        self.text = ""  # cleaned source of this module (its own part of the file)
        self.uses = []  # (absolute path tuple, is_pub) of `use` statements
        self.span = None


ITEM = re.compile(
    r"\b(?:fn|struct|enum|trait|type|const|static|union|macro_rules!)\s+([A-Za-z_][A-Za-z0-9_]*)"
)
MOD_DECL = re.compile(
    r"((?:#\[[^\]]*\]\s*)*)(?:pub(?:\([^)]*\))?\s+)?mod\s+([A-Za-z_][A-Za-z0-9_]*)\s*([;{])"
)
PATH_ATTR = re.compile(r'#\[path\s*=\s*"([^"]+)"\]')


def child_dir(file, is_root):
    """The folder where the children of the module in `file` live."""
    base = os.path.basename(file)
    if is_root or base in ("mod.rs", "lib.rs", "main.rs"):
        return os.path.dirname(file)
    return file[:-3]


def load_module(mod, file, is_root, modules, crate_dir):
    raw = open(file, encoding="utf-8").read()
    no_comments = strip_comments(raw)
    # `#[path]` needs the strings; everything else works on blanked strings.
    clean = strip_test_items(strip_strings(no_comments))
    fill_module(mod, clean, no_comments, 0, len(clean), child_dir(file, is_root), file, modules, crate_dir)


def fill_module(mod, clean, with_strings, start, end, cdir, file, modules, crate_dir):
    """Reads the items of `mod` from clean[start:end]; recurses into `mod x;` and inline
    `mod x { }`."""
    modules.append(mod)
    own = []
    i = start
    while i < end:
        m = MOD_DECL.search(clean, i, end)
        if not m:
            own.append(clean[i:end])
            break
        own.append(clean[i:m.start()])
        name = m.group(2)
        attrs = with_strings[m.start(1):m.end(1)]
        if m.group(3) == ";":
            pm = PATH_ATTR.search(attrs)
            if pm:
                target = os.path.normpath(os.path.join(os.path.dirname(file) if mod.inline is False else cdir, pm.group(1)))
            else:
                a, b = os.path.join(cdir, name + ".rs"), os.path.join(cdir, name, "mod.rs")
                target = a if os.path.exists(a) else b
            if os.path.exists(target):
                child = Module(mod.path + (name,), target)
                mod.children[name] = child
                load_module(child, target, False, modules, crate_dir)
            i = m.end()
        else:
            brace = m.end() - 1
            close = match_brace(clean, brace)
            child = Module(mod.path + (name,), file, inline=True)
            mod.children[name] = child
            fill_module(child, clean, with_strings, brace + 1, close - 1, os.path.join(cdir, name), file, modules, crate_dir)
            i = close
    mod.text = "".join(own)
    mod.items = set(ITEM.findall(mod.text))


# ---------------------------------------------------------------- use trees

USE = re.compile(r"\b(pub(?:\([^)]*\))?\s+)?use\s+([^;]+);")


def expand_use_tree(tree):
    """Paths (lists of segments, last may be '*') named by a use tree, with `as` aliases
    as (path, alias)."""
    tree = re.sub(r"\s+", "", tree)
    out = []

    def split_top(s):
        parts, depth, cur = [], 0, ""
        for ch in s:
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
            else:
                cur += ch
        if cur:
            parts.append(cur)
        return parts

    def walk(prefix, s):
        if not s:
            return
        k = s.find("{")
        if k >= 0 and s.endswith("}"):
            head = s[:k]
            body = s[k + 1 : -1]
            segs = [x for x in head.split("::") if x]
            for part in split_top(body):
                walk(prefix + segs, part)
            return
        out.append((prefix + [x for x in s.split("::") if x], None))

    walk([], tree)
    return out


def parse_uses(text):
    """(segments, alias, is_pub) for every `use` in `text`."""
    found = []
    for m in USE.finditer(text):
        body = m.group(2)
        # keep aliases: turn `x as y` into a marker the expander keeps
        body = re.sub(r"\s+as\s+([A-Za-z_][A-Za-z0-9_]*)", r"@\1", body)
        for segs, _ in expand_use_tree(body):
            alias = None
            if segs and "@" in segs[-1]:
                last, alias = segs[-1].split("@", 1)
                segs = segs[:-1] + [last]
            segs = [s.lstrip(":") for s in segs if s]
            if segs:
                found.append((segs, alias, bool(m.group(1))))
    return found


def without_uses(text):
    return USE.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


# ---------------------------------------------------------------- crate model


class Crate:
    def __init__(self, name, root_file):
        self.name = name
        self.dir = os.path.dirname(os.path.dirname(root_file))
        self.root_file = root_file
        self.modules = []
        self.root = Module((), root_file)
        load_module(self.root, root_file, True, self.modules, self.dir)
        self.by_path = {m.path: m for m in self.modules}
        for m in self.modules:
            m.uses = []
            for segs, alias, is_pub in parse_uses(m.text):
                absolute = self.absolute(m, segs)
                if absolute is None:
                    continue
                m.uses.append((absolute, alias, is_pub))
                if is_pub:
                    if absolute[-1] == "*":
                        m.globs.append(absolute[:-1])
                    elif absolute[-1] == "self":
                        m.reexports[alias or absolute[-2]] = absolute[:-1]
                    else:
                        m.reexports[alias or absolute[-1]] = absolute

    def absolute(self, mod, segs):
        """The absolute path of `segs` seen from `mod`, or None for another crate."""
        base = list(mod.path)
        if segs[0] == "crate":
            return tuple(segs[1:]) or None
        if segs[0] in ("super", "self"):
            i = 0
            while i < len(segs) and segs[i] in ("super", "self"):
                if segs[i] == "super":
                    base = base[:-1]
                i += 1
            rest = segs[i:]
            return tuple(base + rest) if rest or base else None
        # uniform paths: a child module, or a name `use`d into this module
        if segs[0] in mod.children:
            return tuple(base + segs)
        for absolute, alias, _ in getattr(mod, "uses", []):
            name = alias or (absolute[-1] if absolute else None)
            if name == segs[0] and absolute and absolute[-1] != "*":
                return tuple(absolute) + tuple(segs[1:])
        return None

    def resolve(self, path, depth=0):
        """(file, through_root) defining the item or module `path` names; None if not
        in this crate. `through_root`: the name was found via a re-export of the root."""
        if depth > 12 or not path:
            return None
        mod = self.root
        i = 0
        while i < len(path) and path[i] in mod.children:
            mod = mod.children[path[i]]
            i += 1
        if i == len(path) or path[i] in ("*", "self"):
            return (mod.file, False)
        name = path[i]
        if name in mod.items:
            return (mod.file, False)
        if name in mod.reexports:
            target = mod.reexports[name]
            if tuple(target) != tuple(path[: i + 1]):
                r = self.resolve(tuple(target) + tuple(path[i + 1 :]), depth + 1)
                if r:
                    return (r[0], r[1] or mod is self.root)
        for g in mod.globs:
            r = self.resolve(tuple(g) + tuple(path[i:]), depth + 1)
            if r and r[0] != mod.file:
                return (r[0], r[1] or mod is self.root)
        # an enum variant, an associated item, a macro, or something unparsed: the module
        return (mod.file, False)

    def edges(self):
        """{file: {imported file: [how, ...]}} and the list of root re-export uses."""
        graph = {}
        via_root = []
        inline = re.compile(r"(?<![A-Za-z0-9_:])((?:crate|super|self|[a-z_][a-z0-9_]*)(?:::[A-Za-z_][A-Za-z0-9_]*)+)")
        for m in self.modules:
            targets = graph.setdefault(m.file, {})
            refs = [(tuple(a), "use") for a, _, _ in m.uses]
            for p in inline.findall(without_uses(m.text)):
                segs = p.split("::")
                if segs[0] in ("crate", "super", "self") or segs[0] in m.children:
                    a = self.absolute(m, segs)
                    if a:
                        refs.append((a, "path"))
            for a, how in refs:
                r = self.resolve(a)
                if not r:
                    continue
                f, through_root = r
                if through_root and len(a) >= 1 and a[0] not in self.root.children:
                    via_root.append((m.file, "crate::" + "::".join(a)))
                if f != m.file:
                    targets.setdefault(f, set()).add("::".join(a))
        return graph, via_root

    def is_descendant(self, file, ancestor_file):
        """Whether the module in `file` lies below the module in `ancestor_file`."""
        a, d = self.module_of(ancestor_file), self.module_of(file)
        return len(d) > len(a) and d[: len(a)] == a

    def module_of(self, file):
        for m in self.modules:
            if m.file == file and not m.inline:
                return m.path
        return ()


# ---------------------------------------------------------------- graph algorithms


def sccs(graph):
    """Strongly connected components (Tarjan, iterative) with more than one node, and
    self-loops excluded."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    nodes = set(graph) | {t for ts in graph.values() for t in ts}
    for start in sorted(nodes):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                    advanced = True
                    break
                elif w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return sorted(out)


# ---------------------------------------------------------------- main


def crates():
    found = []
    base = os.path.join(ROOT, "crates")
    for name in sorted(os.listdir(base)):
        for root in ("src/lib.rs", "src/main.rs"):
            f = os.path.join(base, name, root)
            if os.path.exists(f):
                found.append((name, f))
    return found


def rel(f):
    return os.path.relpath(f, ROOT)


def short(crate, f):
    return os.path.relpath(f, os.path.join(crate.dir, "src"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true", help="findings only; exit 1 on a circle, an upward import or a use through the root")
    ap.add_argument("--summary", action="store_true", help="findings only")
    ap.add_argument("--crate", help="only this crate (folder name under crates/)")
    ap.add_argument("--strict", action="store_true", help="count a module's use of its own submodules in circles")
    args = ap.parse_args()
    layers = layer_index()
    failures = 0
    for name, root_file in crates():
        if args.crate and args.crate != name:
            continue
        crate = Crate(name, root_file)
        graph, via_root = crate.edges()
        label = f"{name} ({rel(root_file)})"
        print(f"== {label}")
        if not (args.check or args.summary):
            for f in sorted(graph):
                ts = sorted(graph[f])
                print(f"  {short(crate, f)} -> {', '.join(short(crate, t) for t in ts) if ts else '(nothing)'}")
        down = {f: set(t for t in ts if args.strict or not crate.is_descendant(t, f)) for f, ts in graph.items()}
        circles = sccs(down)
        for comp in circles:
            failures += 1
            print(f"  CIRCLE: {' <-> '.join(short(crate, f) for f in comp)}")
            for f in comp:
                for t in sorted(down[f]):
                    if t in comp:
                        print(f"      {short(crate, f)} -> {short(crate, t)} ({', '.join(sorted(graph[f][t])[:3])})")
        if name == "stripkit":
            upward = []
            for f in sorted(graph):
                lf = top(crate, f)
                for t in sorted(graph[f]):
                    lt = top(crate, t)
                    if lf not in layers or lt not in layers:
                        unknown = lf if lf not in layers else lt
                        print(f"  UNLAYERED: module `{unknown}` is not in LAYERS ({short(crate, f)} -> {short(crate, t)})")
                        failures += 1
                        continue
                    if layers[lt] > layers[lf]:
                        upward.append((f, t))
            for f, t in upward:
                failures += 1
                print(f"  UPWARD: {short(crate, f)} [{top(crate, f)}] -> {short(crate, t)} [{top(crate, t)}] ({', '.join(sorted(graph[f][t])[:3])})")
            for f, path in sorted(set(via_root)):
                failures += 1
                print(f"  ROOT RE-EXPORT: {short(crate, f)} uses {path}")
            print(f"  -- {len(circles)} circle(s), {len(upward)} upward import(s), {len(set(via_root))} use(s) through the root's re-exports")
        else:
            print(f"  -- {len(circles)} circle(s)")
    if args.check and failures:
        print(f"imports.py --check: {failures} finding(s)")
        sys.exit(1)


def top(crate, f):
    p = crate.module_of(f)
    return p[0] if p else "lib"


if __name__ == "__main__":
    main()
