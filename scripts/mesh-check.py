#!/usr/bin/env python3
"""Checks a glTF that stripkit wrote from an OBJ or PLY against its source, with readers
nobody here wrote: pygltflib (through gltf-check.py) for the output; trimesh for a PLY
source, and for an OBJ source a plain parser in this script (v, vt, vn, usemtl; fans),
since trimesh 4's OBJ loader gives some of spot's corners another UV (631 of 5,856
triangles differ from a plain reading of the file). For issue #15's round trips of spot (UVs), horse (normals) and an OBJ with two
materials.

    python3 scripts/mesh-check.py SOURCE.obj|ply OUT.glb|gltf

What must hold: the source's materials, each named by a primitive or several (one per
OBJ object, `o`, where the writer keeps them apart), whose triangles together are the
source's triangles of that material (quads fanned from their first corner), compared as
oriented triangles by their corners' values: position, TEXCOORD_0 (glTF's v = 1 - OBJ's
v) and NORMAL where the source has them, as float32. Negative (relative) OBJ indices
count back from the face's line. Exit 1 on a difference.

Needs: pip install trimesh pygltflib numpy
"""
import collections
import importlib.util
import os
import sys

import numpy as np
import trimesh

spec = importlib.util.spec_from_file_location("gltf_check", os.path.join(os.path.dirname(__file__), "gltf-check.py"))
gc = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gc)


def f32(a):
    return np.asarray(a, np.float32)


def absolute(text, n):
    """An OBJ index (1-based, or negative: relative to the n elements read so far), 0-based."""
    if not text:
        return None
    i = int(text)
    return i - 1 if i > 0 else n + i


def obj_parts(path):
    """The OBJ read plainly: per usemtl (in order of first use), its fanned faces."""
    v, vt, vn, faces = [], [], [], collections.OrderedDict()
    material = None
    for line in open(path):
        s = line.split()
        if not s:
            continue
        if s[0] == "v":
            v.append([float(x) for x in s[1:4]])
        elif s[0] == "vt":
            vt.append([float(x) for x in s[1:3]])
        elif s[0] == "vn":
            vn.append([float(x) for x in s[1:4]])
        elif s[0] == "usemtl":
            material = s[1]
        elif s[0] == "f":
            # A negative index counts back from the elements read so far (Cornell box).
            counts = (len(v), len(vt), len(vn))
            corners = [[absolute(t, n) for t, n in zip((c.split("/") + ["", ""])[:3], counts)] for c in s[1:]]
            faces.setdefault(material, []).append(corners)
    names = ["POSITION"] + (["TEXCOORD_0"] if vt else []) + (["NORMAL"] if vn else [])

    def key(c):
        out = [tuple(f32(v[c[0]]).tolist())]
        if vt:
            u, w = f32(vt[c[1]])
            out.append((float(u), float(np.float32(1.0) - w)))
        if vn:
            out.append(tuple(f32(vn[c[2]]).tolist()))
        return tuple(out)

    parts = []
    for name, fs in faces.items():
        tris = collections.Counter()
        for f in fs:
            for i in range(1, len(f) - 1):
                tris[gc.canonical([key(f[0]), key(f[i]), key(f[i + 1])])] += 1
        parts.append((name, names, tris))
    return parts


def source_parts(path):
    """(material name or None, triangles as tuples of corner keys) per part."""
    if path.endswith(".obj"):
        return obj_parts(path)
    loaded = trimesh.load(path, process=False, maintain_order=True)
    geoms = list(loaded.geometry.items()) if isinstance(loaded, trimesh.Scene) else [(None, loaded)]
    parts = []
    for name, m in geoms:
        cols = [f32(m.vertices)]
        names = ["POSITION"]
        uv = getattr(m.visual, "uv", None)
        if uv is not None and len(uv) == len(m.vertices):
            uv = f32(uv).copy()
            uv[:, 1] = np.float32(1.0) - uv[:, 1]
            cols.append(uv)
            names.append("TEXCOORD_0")
        if path.endswith(".ply") and "vertex_normals" in m._cache.cache:
            # glTF wants unit normals: stripkit rescales those off unit length (its
            # documented repair; a PLY's nx ny nz need not be unit), so the check does too.
            n = np.asarray(m._cache.cache["vertex_normals"], np.float64)
            length = np.sqrt(n[:, 0] * n[:, 0] + n[:, 1] * n[:, 1] + n[:, 2] * n[:, 2])
            scale = np.where(np.abs(length - 1.0) > 1e-4, 1.0 / length, 1.0)
            cols.append(f32(n * scale[:, None]))
            names.append("NORMAL")
        keys = [tuple(tuple(c[v].tolist()) for c in cols) for v in range(len(m.vertices))]
        tris = collections.Counter(gc.canonical([keys[v] for v in f]) for f in m.faces)
        parts.append((name, names, tris))
    return parts


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    src, out = sys.argv[1], sys.argv[2]
    parts = source_parts(src)
    b = gc.Asset(out)
    prims = []
    for mesh in b.g.meshes:
        logical, failures = gc.logical_primitives(b, mesh)
        if failures:
            print("FAIL:", failures)
            sys.exit(1)
        prims += logical
    failures = []
    # An OBJ's objects (o) may each keep their own primitive: a material's triangles are
    # those of every primitive that names it.
    by_material = collections.defaultdict(list)
    for desc, p, tris in prims:
        mat = b.g.materials[p.material].name if p.material is not None else None
        by_material[mat].append((desc, p, tris))
    if len(by_material) != len(parts):
        failures.append(f"{len(parts)} materials in the source, {len(by_material)} written")
    for name, names, want in parts:
        got = by_material.get(name) if name is not None else (prims if len(by_material) == 1 else None)
        if not got:
            failures.append(f"no primitive with material {name}")
            continue
        have = collections.Counter()
        lost = []
        for desc, p, tris in got:
            names_out, values = gc.attribute_table(b, p)
            lost += [n for n in names if n not in names_out]
            if not lost:
                have.update(gc.canonical([tuple(tuple(f32(values[n][v]).tolist()) for n in names) for v in t])
                            for t in tris)
        if lost:
            failures.append(f"material {name}: attributes {sorted(set(lost))} lost")
            continue
        desc = got[0][0] if len(got) == 1 else f"{len(got)} primitives"
        same = have == want
        print(f"material {name}: {sum(want.values())} triangles, attributes {names}, {desc}: "
              f"{'same' if same else 'DIFFERENT'}")
        if not same:
            failures.append(f"material {name}: {sum((want - have).values())} triangles lost, "
                            f"{sum((have - want).values())} added (by corner values)")
    for f in failures:
        print("FAIL:", f)
    print("ok" if not failures else f"{len(failures)} failures")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
