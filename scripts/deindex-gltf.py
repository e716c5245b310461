#!/usr/bin/env python3
"""Writes a .glb with every indexed triangle primitive (list or strip) de-indexed: each index becomes
a vertex of its own (attributes and morph targets gathered), the `indices` dropped, as
exporters write flat-shaded meshes. For the weld figures of
docs/experiments/weld-and-materials.md:
    python3 scripts/deindex-gltf.py IN.glb OUT.glb [--seed N]
--seed shuffles the triangles (same seed, same order). Needs numpy."""
import json, struct, sys
import numpy as np

COMP = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def read_glb(path):
    data = open(path, "rb").read()
    magic, _, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67, "not a glb"
    pos, doc, bin_ = 12, None, b""
    while pos < length:
        size, kind = struct.unpack_from("<II", data, pos)
        chunk = data[pos + 8 : pos + 8 + size]
        if kind == 0x4E4F534A:
            doc = json.loads(chunk)
        elif kind == 0x004E4942:
            bin_ = chunk
        pos += 8 + size
    return doc, bin_


def element_bytes(doc, bin_, a):
    acc = doc["accessors"][a]
    view = doc["bufferViews"][acc["bufferView"]]
    dtype = np.dtype(COMP[acc["componentType"]])
    width = dtype.itemsize * NCOMP[acc["type"]]
    stride = view.get("byteStride", width)
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    rows = [bin_[start + i * stride : start + i * stride + width] for i in range(acc["count"])]
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(acc["count"], width)


def main():
    src, dst = sys.argv[1], sys.argv[2]
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else None
    doc, bin_ = read_glb(src)
    out = bytearray()

    def add(raw, like, extra):
        while len(out) % 4:
            out.append(0)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(out), "byteLength": len(raw)})
        out.extend(raw)
        acc = {k: v for k, v in like.items() if k not in ("bufferView", "byteOffset", "sparse", "min", "max", "name")}
        acc.update(bufferView=len(doc["bufferViews"]) - 1, **extra)
        doc["accessors"].append(acc)
        return len(doc["accessors"]) - 1

    old_views = len(doc["bufferViews"])
    original = json.loads(json.dumps(doc))
    for m, mesh in enumerate(doc["meshes"]):
        mesh.get("extensions", {}).pop("EXT_mesh_primitive_restart", None)
        if mesh.get("extensions") == {}:
            del mesh["extensions"]
        for p, prim in enumerate(mesh["primitives"]):
            mode = prim.get("mode", 4)
            if "indices" not in prim or mode not in (4, 5):
                continue
            ia = original["accessors"][prim["indices"]]
            indices = element_bytes(original, bin_, prim.pop("indices")).view(COMP[ia["componentType"]]).reshape(-1)
            if mode == 5:
                # A strip (no restart): triangle i is (i, i+1, i+2), every other one
                # turned back; degenerate ones dropped.
                s = indices.astype(np.int64)
                t = np.stack([s[:-2], s[1:-1], s[2:]], axis=1)
                odd = np.arange(len(t)) % 2 == 1
                t[odd] = t[odd][:, [1, 0, 2]]
                keep = (t[:, 0] != t[:, 1]) & (t[:, 1] != t[:, 2]) & (t[:, 0] != t[:, 2])
                indices = t[keep].reshape(-1)
                prim["mode"] = 4
            tris = indices.reshape(-1, 3)
            if seed is not None:
                tris = tris[np.random.default_rng(seed).permutation(len(tris))]
            flat = tris.reshape(-1).astype(np.int64)

            def gather(a, name):
                rows = element_bytes(original, bin_, a)[flat]
                extra = {"count": len(flat)}
                if name == "POSITION":
                    v = rows.view(np.float32).reshape(len(flat), 3)
                    extra.update(min=v.min(axis=0).tolist(), max=v.max(axis=0).tolist())
                return add(rows.tobytes(), original["accessors"][a], extra)

            prim["attributes"] = {k: gather(a, k) for k, a in prim["attributes"].items()}
            if "targets" in prim:
                prim["targets"] = [{k: gather(a, k) for k, a in t.items()} for t in prim["targets"]]
    # Keep the old data as it was (other primitives may use it): old views over the old bytes.
    base = len(bin_) + (-len(bin_)) % 4
    for v in doc["bufferViews"][old_views:]:
        v["byteOffset"] += base
    bin_all = bin_ + b"\0" * ((-len(bin_)) % 4) + bytes(out)
    if "extensionsUsed" in doc:
        doc["extensionsUsed"] = [e for e in doc["extensionsUsed"] if e != "EXT_mesh_primitive_restart"] or None
        if doc["extensionsUsed"] is None:
            del doc["extensionsUsed"]
    doc["buffers"] = [{"byteLength": len(bin_all)}]
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * ((-len(js)) % 4)
    bin_all += b"\0" * ((-len(bin_all)) % 4)
    total = 12 + 8 + len(js) + 8 + len(bin_all)
    with open(dst, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, total))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(bin_all), 0x004E4942) + bin_all)


if __name__ == "__main__":
    main()
