#!/usr/bin/env python3
"""Checks a glTF written by stripkit against the file it came from, with a reader
nobody here wrote (pygltflib + numpy), for issue #15's round-trip targets.

    python3 scripts/gltf-check.py IN.gltf|glb OUT.gltf|glb [--json]

What must hold (exit 1 and a line per failure otherwise):
  * the same scenes, nodes (children, mesh, skin, transform), materials, textures,
    images, samplers, skins, animations, cameras; the input's extensionsUsed kept;
  * the same meshes, and per mesh the same primitives in order, where a group of
    EXT_mesh_primitive_restart counts as one primitive (its restart accessor), and its
    fallback primitives must draw the same triangles as the group;
  * per primitive: the same material, the same attribute names, the same morph-target
    count, and the same multiset of oriented triangles, each triangle compared by the
    values of every attribute and morph-target attribute at its corners (so a
    renumbering of vertices passes, a lost UV, a moved target delta or a flipped
    triangle does not). Degenerate triangles (a repeated index) are not triangles.

Needs: pip install pygltflib numpy
"""
import base64
import collections
import json
import os
import sys

import numpy as np
import pygltflib

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
DTYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
RESTART = {5121: 0xFF, 5123: 0xFFFF, 5125: 0xFFFFFFFF}
EXT = "EXT_mesh_primitive_restart"


class Asset:
    def __init__(self, path):
        self.path = path
        self.g = pygltflib.GLTF2().load(path)
        self.buffers = []
        for i, b in enumerate(self.g.buffers):
            if b.uri is None:
                self.buffers.append(bytes(self.g.binary_blob() or b""))
            elif b.uri.startswith("data:"):
                self.buffers.append(base64.b64decode(b.uri.split(",", 1)[1]))
            else:
                with open(os.path.join(os.path.dirname(path), b.uri), "rb") as f:
                    self.buffers.append(f.read())

    def accessor(self, i):
        a = self.g.accessors[i]
        if a.sparse is not None:
            raise ValueError(f"{self.path}: accessor {i} is sparse (not checked here)")
        n = COMPONENTS[a.type]
        dt = np.dtype(DTYPES[a.componentType])
        if a.bufferView is None:
            return np.zeros((a.count, n), dt)
        bv = self.g.bufferViews[a.bufferView]
        data = self.buffers[bv.buffer]
        start = (bv.byteOffset or 0) + (a.byteOffset or 0)
        stride = bv.byteStride or n * dt.itemsize
        out = np.empty((a.count, n), dt)
        for k in range(a.count):
            out[k] = np.frombuffer(data, dt, n, start + k * stride)
        return out

    def indices(self, i):
        return self.accessor(i)[:, 0].astype(np.int64)


def triangles(mode, idx):
    """Oriented triangles of one primitive's index list (restart values already split)."""
    out = []
    if mode == 4:
        for k in range(0, len(idx) - 2, 3):
            out.append((idx[k], idx[k + 1], idx[k + 2]))
    elif mode == 5:
        for k in range(len(idx) - 2):
            a, b, c = idx[k], idx[k + 1], idx[k + 2]
            out.append((a, b, c) if k % 2 == 0 else (b, a, c))
    elif mode == 6:
        for k in range(1, len(idx) - 1):
            out.append((idx[k], idx[k + 1], idx[0]))
    return [t for t in out if len(set(t)) == 3]


def split_restart(idx, value):
    runs, cur = [], []
    for v in idx:
        if v == value:
            runs.append(cur)
            cur = []
        else:
            cur.append(v)
    runs.append(cur)
    return runs


def canonical(corners):
    """An oriented triangle of corner keys, rotated so its smallest key comes first."""
    k = min(range(3), key=lambda i: corners[i])
    return tuple(corners[(k + i) % 3] for i in range(3))


def logical_primitives(asset, mesh):
    """(description, representative primitive, oriented triangles by vertex index) per
    logical primitive; also a list of failures about the restart groups."""
    prims = mesh.primitives
    groups = []
    failures = []
    ext = (mesh.extensions or {}).get(EXT)
    grouped = {}
    if ext:
        for gi, grp in enumerate(ext.get("primitiveGroups", [])):
            for p in grp["primitives"]:
                grouped[p] = gi
            groups.append(grp)
    seen = set()
    out = []
    for pi, p in enumerate(prims):
        if pi in grouped:
            gi = grouped[pi]
            if gi in seen:
                continue
            seen.add(gi)
            grp = groups[gi]
            comp = asset.g.accessors[grp["indices"]].componentType
            idx = asset.indices(grp["indices"])
            tris = []
            for run in split_restart(idx, RESTART[comp]):
                tris += triangles(p.mode, run)
            fallback = []
            for q in grp["primitives"]:
                fallback += triangles(prims[q].mode, asset.indices(prims[q].indices))
            if collections.Counter(map(canonical, tris)) != collections.Counter(map(canonical, fallback)):
                failures.append(f"restart group {gi}: its fallback primitives draw other triangles")
            out.append((f"restart group {gi} ({len(grp['primitives'])} fallback primitives)", p, tris))
        else:
            idx = asset.indices(p.indices) if p.indices is not None else np.arange(
                asset.g.accessors[p.attributes.POSITION].count)
            out.append((f"primitive {pi}", p, triangles(p.mode if p.mode is not None else 4, idx)))
    return out, failures


def attribute_table(asset, prim):
    names = sorted(k for k, v in prim.attributes.__dict__.items() if v is not None)
    return names, {n: asset.accessor(getattr(prim.attributes, n)) for n in names}


def corner_table(asset, prim):
    """The attributes and every morph target's attributes ("target 0 POSITION"), by name."""
    names, values = attribute_table(asset, prim)
    for ti, target in enumerate(prim.targets or []):
        for attr, acc in sorted(target.items()):
            names.append(f"target {ti} {attr}")
            values[names[-1]] = asset.accessor(acc)
    return names, values


def corner_key(values, names, v):
    return tuple(tuple(values[n][v].tolist()) for n in names)


def strip_indices(obj):
    """JSON of the non-mesh parts, for comparison."""
    d = json.loads(obj.to_json()) if hasattr(obj, "to_json") else obj
    return d


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        print(__doc__)
        sys.exit(2)
    a, b = Asset(args[0]), Asset(args[1])
    failures = []
    report = {"input": args[0], "output": args[1], "primitives": []}
    ja, jb = json.loads(a.g.to_json()), json.loads(b.g.to_json())
    for key in ["scenes", "nodes", "materials", "textures", "samplers", "skins", "cameras"]:
        if ja.get(key) != jb.get(key):
            failures.append(f"{key} differ")
    for key in ["images", "animations"]:
        if len(ja.get(key) or []) != len(jb.get(key) or []):
            failures.append(f"{key}: {len(ja.get(key) or [])} in, {len(jb.get(key) or [])} out")
    for i, (anim_a, anim_b) in enumerate(zip(ja.get("animations") or [], jb.get("animations") or [])):
        for ch_a, ch_b in zip(anim_a["channels"], anim_b["channels"]):
            if ch_a["target"] != ch_b["target"]:
                failures.append(f"animation {i}: a channel targets another node or path")
        for s_a, s_b in zip(anim_a["samplers"], anim_b["samplers"]):
            if not np.array_equal(a.accessor(s_a["input"]), b.accessor(s_b["input"])) or not np.array_equal(
                    a.accessor(s_a["output"]), b.accessor(s_b["output"])):
                failures.append(f"animation {i}: sampler data differ")
    if ja.get("scene") != jb.get("scene"):
        failures.append("the default scene differs")
    missing = set(ja.get("extensionsUsed") or []) - set(jb.get("extensionsUsed") or [])
    # Restart groups go with --join degenerate (the output has none left to list).
    if not any((m.get("extensions") or {}).get("EXT_mesh_primitive_restart") for m in jb.get("meshes") or []):
        missing.discard("EXT_mesh_primitive_restart")
    if missing:
        failures.append(f"extensionsUsed lost: {sorted(missing)}")
    if len(a.g.meshes) != len(b.g.meshes):
        failures.append(f"{len(a.g.meshes)} meshes in, {len(b.g.meshes)} out")
    for mi, (ma, mb) in enumerate(zip(a.g.meshes, b.g.meshes)):
        if ma.name != mb.name or ma.weights != mb.weights:
            failures.append(f"mesh {mi}: name or weights differ")
        la, _ = logical_primitives(a, ma)
        lb, fb = logical_primitives(b, mb)
        failures += [f"mesh {mi}: {f}" for f in fb]
        if len(la) != len(lb):
            failures.append(f"mesh {mi}: {len(la)} primitives in, {len(lb)} out")
        for pi, ((_, pa, ta), (desc, pb, tb)) in enumerate(zip(la, lb)):
            where = f"mesh {mi} primitive {pi}"
            if pa.material != pb.material:
                failures.append(f"{where}: material {pa.material} in, {pb.material} out")
            na, va = corner_table(a, pa)
            nb, vb = corner_table(b, pb)
            if na != nb:
                failures.append(f"{where}: attributes {na} in, {nb} out")
                continue
            if len(pa.targets or []) != len(pb.targets or []):
                failures.append(f"{where}: morph targets differ")
            ca = collections.Counter(canonical([corner_key(va, na, v) for v in t]) for t in ta)
            cb = collections.Counter(canonical([corner_key(vb, nb, v) for v in t]) for t in tb)
            ok = ca == cb
            if not ok:
                lost = sum((ca - cb).values())
                added = sum((cb - ca).values())
                failures.append(f"{where}: {lost} triangles lost, {added} added (by corner values)")
            mode_in = pa.mode if pa.mode is not None else 4
            idx_in = a.g.accessors[pa.indices].count if pa.indices is not None else None
            out_acc = b.g.accessors[pb.indices].count if pb.indices is not None else None
            if desc.startswith("restart"):
                grp_acc = [g for g in (mb.extensions or {})[EXT]["primitiveGroups"] if
                           mb.primitives.index(pb) in g["primitives"]][0]["indices"]
                out_acc = b.g.accessors[grp_acc].count
            report["primitives"].append({"where": where, "out": desc, "triangles": len(ta),
                                         "mode_in": mode_in, "indices_in": idx_in,
                                         "mode_out": pb.mode, "indices_out": out_acc,
                                         "attributes": na, "same": ok})
    report["failures"] = failures
    if "--json" in sys.argv:
        print(json.dumps(report, indent=1))
    else:
        for p in report["primitives"]:
            print(f"{p['where']}: {p['triangles']} triangles, {p['indices_in']} indices (mode {p['mode_in']}) -> "
                  f"{p['indices_out']} (mode {p['mode_out']}, {p['out']}), attributes {','.join(p['attributes'])}: "
                  f"{'same' if p['same'] else 'DIFFERENT'}")
        for f in failures:
            print("FAIL:", f)
        print("ok" if not failures else f"{len(failures)} failures")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
