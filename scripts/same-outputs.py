#!/usr/bin/env python3
"""Compares two folders written by scripts/same-outputs.sh: every file byte for byte,
JSON reports without their timings and paths, text reports without times. Also compares
the strip hashes and the bench table's figures (its ms columns left out) when the folders'
parents hold them. Exit 1 when anything else differs."""
import difflib, json, os, re, sys

TIMED = re.compile(r"(ms|us|us_max|_max|seconds|time|input|output|file)$")


def norm(x):
    if isinstance(x, dict):
        return {k: norm(v) for k, v in x.items() if not TIMED.search(k) and not k.startswith("us_")}
    if isinstance(x, list):
        return [norm(v) for v in x]
    return x


def text(t):
    t = re.sub(r"\S*/out/", "OUT/", t)
    return [l for l in re.sub(r"\d+(\.\d+)?\s*(ms|µs|us|s)\b", "T", t).splitlines() if "stripify " not in l]


def main(a, b):
    bad = 0
    for name in sorted(set(os.listdir(a)) | set(os.listdir(b))):
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if not (os.path.exists(pa) and os.path.exists(pb)):
            print(f"only in one: {name}")
            bad += 1
            continue
        x, y = open(pa, "rb").read(), open(pb, "rb").read()
        if x == y:
            continue
        try:
            if norm(json.loads(x)) == norm(json.loads(y)):
                continue
        except ValueError:
            pass
        if name.endswith((".txt", ".err")):
            tx = text(x.decode("utf8", "replace"))
            ty = text(y.decode("utf8", "replace"))
            if tx == ty:
                continue
            print("\n".join(list(difflib.unified_diff(tx, ty, name, name, lineterm=""))[:12]))
        print(f"differs: {name}")
        bad += 1
    for extra, pick in (("hashes.txt", lambda l: "|" in l), ("bench-strips.md", lambda l: l.startswith("|"))):
        fa, fb = (os.path.join(os.path.dirname(os.path.abspath(d)), extra) for d in (a, b))
        if os.path.exists(fa) and os.path.exists(fb):
            cut = (lambda l: "|".join(c for i, c in enumerate(l.split("|")) if i not in (12, 13))) if extra.endswith(".md") else (lambda l: l)
            la = [cut(l) for l in open(fa) if pick(l)]
            lb = [cut(l) for l in open(fb) if pick(l)]
            same = la == lb
            print(f"{extra}: {len(la)} rows, {'identical' if same else 'DIFFERENT'}")
            bad += 0 if same else 1
    print(f"{bad} difference(s) beyond timings and paths")
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: same-outputs.py OLD/out NEW/out")
    sys.exit(main(sys.argv[1], sys.argv[2]))
