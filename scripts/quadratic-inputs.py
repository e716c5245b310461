#!/usr/bin/env python3
"""Writes the "quadratic inputs" of issue #30 (class 3, mesh parts) at a given size.

    quadratic-inputs.py KIND N OUT

KIND:
  usemtl     an OBJ strip of N triangles, one `usemtl` (a material of its own) per face
  ribbon     the same strip of N triangles without materials (for `lod build`)
  edge       an OBJ of N triangles sharing the edge 1-2 (a book of N pages)
  stl-same   a binary STL of N identical triangles
  ply-props  an ASCII PLY with one triangle whose vertices carry N extra uchar properties
  grid       an OBJ grid of about N triangles (for `balanced --cache`)
  star       a DIMACS graph: node 1 joined to N leaves, weight 1 (for `match`)
  path-mod7  a DIMACS path of N nodes, edge i (0-based) of weight i mod 7 (for `match`)

Used for the growth tables in docs/experiments/reliability.md ("Quadratic inputs";
`star` and `path-mod7`: "The matching on stars and tie-heavy paths").
"""
import math
import struct
import sys


def main():
    kind, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    if kind in ("usemtl", "ribbon"):
        lines = []
        for i in range(n // 2 + 2):
            lines.append(f"v {i} 0 0\nv {i} 1 0\n")
        for i in range(n):
            a = 2 * (i // 2) + 1
            if kind == "usemtl":
                lines.append(f"usemtl m{i}\n")
            if i % 2 == 0:
                lines.append(f"f {a} {a + 2} {a + 1}\n")
            else:
                lines.append(f"f {a + 1} {a + 2} {a + 3}\n")
        open(out, "w").write("".join(lines))
    elif kind == "edge":
        lines = ["v 0 0 0\nv 1 0 0\n"]
        for i in range(n):
            t = 2 * math.pi * i / n
            lines.append(f"v 0.5 {math.cos(t)} {math.sin(t)}\n")
        for i in range(n):
            lines.append(f"f 1 2 {i + 3}\n")
        open(out, "w").write("".join(lines))
    elif kind == "stl-same":
        tri = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
        with open(out, "wb") as f:
            f.write(b"\0" * 80 + struct.pack("<I", n) + tri * n)
    elif kind == "ply-props":
        head = ["ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"]
        head += [f"property uchar p{i}\n" for i in range(n)]
        head.append("element face 1\nproperty list uchar int vertex_indices\nend_header\n")
        zeros = " 0" * n
        body = [f"0 0 0{zeros}\n", f"1 0 0{zeros}\n", f"0 1 0{zeros}\n", "3 0 1 2\n"]
        open(out, "w").write("".join(head + body))
    elif kind == "grid":
        k = max(1, int(math.sqrt(n / 2)))
        lines = [f"v {x} {y} 0\n" for y in range(k + 1) for x in range(k + 1)]
        for y in range(k):
            for x in range(k):
                a = y * (k + 1) + x + 1
                lines.append(f"f {a} {a + 1} {a + k + 2}\nf {a} {a + k + 2} {a + k + 1}\n")
        open(out, "w").write("".join(lines))
    elif kind == "star":
        lines = [f"p edge {n + 1} {n}\n"]
        lines += [f"e 1 {i + 2} 1\n" for i in range(n)]
        open(out, "w").write("".join(lines))
    elif kind == "path-mod7":
        lines = [f"p edge {n} {n - 1}\n"]
        lines += [f"e {i + 1} {i + 2} {i % 7}\n" for i in range(n - 1)]
        open(out, "w").write("".join(lines))
    else:
        sys.exit(f"unknown kind {kind}")


if __name__ == "__main__":
    main()
