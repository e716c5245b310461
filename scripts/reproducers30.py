#!/usr/bin/env python3
"""Runs the hostile examples of issue #30 at the sizes the issue gives, through the
release CLI, each under the audit's 1.5 GB address-space cap, and prints one row per
example: the exit code, the wall seconds, the peak resident memory, and whether it
met the issue's targets (an expected exit code, no panic or abort, a peak under
1 GiB, under 2 s).

    scripts/reproducers30.py [STRIPKIT] [--keep DIR]

STRIPKIT defaults to target/release/stripkit (build it first:
`cargo build --release -p stripkit-cli`). The tests check each example's exit code
and message at smaller sizes (crates/stripkit-cli/tests); this script is for the
time and memory figures, which do not belong in tests. Exit status 1 if any row
misses its target.
"""
import json
import math
import os
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import time

GIB = 1 << 30
CAP = 1_500_000_000  # the audit's address-space cap
LIMIT_S = 2.0


def limit_as():
    resource.setrlimit(resource.RLIMIT_AS, (CAP, CAP))


def run(cmd, cwd):
    """Runs `cmd` under the cap; returns (exit code, wall seconds, peak RSS bytes, stderr)."""
    with tempfile.TemporaryFile() as err:
        start = time.monotonic()
        out = tempfile.TemporaryFile()
        p = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                             preexec_fn=limit_as)
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() - start > 30:
                p.kill()
                pid, status, usage = os.wait4(p.pid, 0)
                break
            time.sleep(0.002)
        wall = time.monotonic() - start
        p.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        text = err.read().decode("utf-8", "replace")
        out.seek(0)
        run.stdout = out.read().decode("utf-8", "replace")
        out.close()
    return p.returncode, wall, usage.ru_maxrss * 1024, text


def run_piped(cmd, cwd):
    """`cmd | head -c 10`, returning the exit code of `cmd` (the closed pipe case)."""
    start = time.monotonic()
    p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=limit_as)
    p.stdout.read(10)
    p.stdout.close()
    err = p.stderr.read()
    p.wait()
    return p.returncode, time.monotonic() - start, None, err.decode("utf-8", "replace")


# ---------------------------------------------------------------- inputs

def w(path, data):
    mode = "wb" if isinstance(data, (bytes, bytearray)) else "w"
    with open(path, mode) as f:
        f.write(data)
    return path


def obj_ribbon(n, materials):
    lines = [f"v {i} 0 0\nv {i} 1 0\n" for i in range(n // 2 + 2)]
    for i in range(n):
        a = 2 * (i // 2) + 1
        if materials:
            lines.append(f"usemtl m{i}\n")
        lines.append(f"f {a} {a + 2} {a + 1}\n" if i % 2 == 0 else f"f {a + 1} {a + 2} {a + 3}\n")
    return "".join(lines)


def obj_book(n):
    lines = ["v 0 0 0\nv 1 0 0\n"]
    for i in range(n):
        t = 2 * math.pi * i / n
        lines.append(f"v 0.5 {math.cos(t)} {math.sin(t)}\n")
    lines += [f"f 1 2 {i + 3}\n" for i in range(n)]
    return "".join(lines)


def stl_same(n):
    tri = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    return b"\0" * 80 + struct.pack("<I", n) + tri * n


def ply_props(n, binary):
    head = "ply\nformat {} 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    head = head.format("binary_little_endian" if binary else "ascii")
    head += "".join(f"property uchar p{i}\n" for i in range(n))
    head += "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    if binary:
        body = b""
        for x, y in [(0, 0), (1, 0), (0, 1)]:
            body += struct.pack("<3f", x, y, 0) + b"\0" * n
        body += struct.pack("<B3i", 3, 0, 1, 2)
        return head.encode() + body
    zeros = " 0" * n
    return head + f"0 0 0{zeros}\n1 0 0{zeros}\n0 1 0{zeros}\n3 0 1 2\n"


def dimacs_star(leaves):
    lines = [f"p edge {leaves + 1} {leaves}\n"]
    lines += [f"e 1 {i + 2} 1\n" for i in range(leaves)]
    return "".join(lines)


def dimacs_path(n, mod):
    lines = [f"p edge {n} {n - 1}\n"]
    lines += [f"e {i + 1} {i + 2} {i % mod}\n" for i in range(n - 1)]
    return "".join(lines)


def glb(doc, bin_):
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_ = bytes(bin_) + b"\0" * (-len(bin_) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_), 0x004E4942) + bin_
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def glb_primitives(n):
    """n primitives of one triangle each, every one with its own accessors and views."""
    bin_ = bytearray()
    views, accessors, prims = [], [], []
    for i in range(n):
        off = len(bin_)
        bin_ += struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
        views += [{"buffer": 0, "byteOffset": off, "byteLength": 36},
                  {"buffer": 0, "byteOffset": off + 36, "byteLength": 6}]
        accessors += [{"bufferView": 2 * i, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 2 * i + 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
        prims.append({"attributes": {"POSITION": 2 * i}, "indices": 2 * i + 1})
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(bin_)}], "bufferViews": views,
           "accessors": accessors, "meshes": [{"primitives": prims}], "nodes": [{"mesh": 0}],
           "scenes": [{"nodes": [0]}], "scene": 0}
    return glb(doc, bin_)


def glb_short_target():
    """4 positions (two triangles) and a morph target of count 2."""
    pos = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    tgt = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    bin_ = pos + idx + tgt
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(bin_)}],
           "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                           {"buffer": 0, "byteOffset": 60, "byteLength": 24}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 0]},
                         {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                         {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3",
                          "min": [0, 0, 1], "max": [0, 0, 1]}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "targets": [{"POSITION": 2}]}],
                       "weights": [0.5]}],
           "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
    return glb(doc, bin_)


def glb_extension(required, draco):
    """A one-triangle glb naming an extension (`draco`: Draco on its primitive)."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    bin_ = pos + idx
    prim = {"attributes": {"POSITION": 0}, "indices": 1}
    name = "KHR_draco_mesh_compression" if draco else "EXT_unknown_geometry"
    if draco:
        prim["extensions"] = {name: {"bufferView": 1, "attributes": {"POSITION": 0}}}
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(bin_)}],
           "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 0]},
                         {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
           "meshes": [{"primitives": [prim]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
           "extensionsUsed": [name]}
    if required:
        doc["extensionsRequired"] = [name]
    return glb(doc, bin_)


def jitter(src, dst):
    """`src` with every coordinate moved by a deterministic pseudo-random 0.1%."""
    out, k = [], 1
    for line in open(src):
        if line.startswith("v "):
            xyz = []
            for t in line.split()[1:4]:
                k = (k * 1103515245 + 12345) % (1 << 31)
                xyz.append(float(t) * (1 + 0.002 * (k / (1 << 31) - 0.5)))
            out.append("v {!r} {!r} {!r}\n".format(*xyz))
        else:
            out.append(line)
    return w(dst, "".join(out))


def scaled_obj(src, scale, dst):
    out = []
    for line in open(src):
        if line.startswith("v "):
            x, y, z = (float(t) * scale for t in line.split()[1:4])
            out.append(f"v {x!r} {y!r} {z!r}\n")
        else:
            out.append(line)
    return w(dst, "".join(out))


# ---------------------------------------------------------------- the table

def examples(sk, d):
    """(class, name, command, accepted exit codes); inputs written into `d` lazily."""
    p = lambda name: os.path.join(d, name)
    small = p("small.obj")
    subprocess.run([sk, "gen", "torus", "-o", p("torus.obj")], check=True, stdout=subprocess.DEVNULL)
    # Jittered, so that the simplifier meets no exact ties: a symmetric torus scaled by
    # anything but a power of two rounds its ties differently (x3 changes the result
    # as much as x1e20), which would hide what the scale itself does.
    jitter(p("torus.obj"), small)
    big = p("big.ply")
    subprocess.run([sk, "gen", "icosphere", "8", "-o", big], check=True, stdout=subprocess.DEVNULL)
    frames = p("frames")
    os.makedirs(frames, exist_ok=True)
    for i in range(3):
        scaled_obj(small, 1.0 + 0.1 * i, os.path.join(frames, f"f{i}.obj"))
    ok = (0,)
    bad = (2,)
    e = []
    e.append((1, "morph target count 2 < POSITION 4, strip -o .glb", lambda: w(p("short.glb"), glb_short_target()),
              [sk, "strip", p("short.glb"), "-o", p("o1.glb")], bad))
    e.append((2, "match: DIMACS star of 20,000 leaves", lambda: w(p("star.dimacs"), dimacs_star(20000)),
              [sk, "match", p("star.dimacs")], (0, 2)))
    e.append((2, "PLY with 300,000 one-byte vertex properties", lambda: w(p("props.ply"), ply_props(300000, True)),
              [sk, "strip", p("props.ply"), "-o", p("o2.ply")], (0, 2)))
    e.append((2, "glb with 80,000 primitives", lambda: w(p("prims80k.glb"), glb_primitives(80000)),
              [sk, "strip", p("prims80k.glb"), "-o", p("o3.glb")], (0, 2)))
    e.append((2, "distance --samples 1e8", None, [sk, "distance", small, small, "--samples", "100000000"], bad))
    e.append((2, "lod build-seq --samples 1e8", None,
              [sk, "lod", "build-seq", frames, "-o", p("o.lodseq"), "--samples", "100000000"], bad))
    e.append((2, "cull --views 1e8", None, [sk, "cull", small, "--views", "100000000"], bad))
    e.append((2, "gen grid 13000 13000", None, [sk, "gen", "grid", "13000", "13000", "-o", p("g.obj")], bad))
    e.append((2, "render --size 4096x4096 --wireframe, 1.3M triangles", None,
              [sk, "render", big, "-o", p("r.png"), "--size", "4096x4096", "--wireframe"], (0, 2)))
    e.append((3, "strip: one usemtl per face, 16k faces", lambda: w(p("usemtl.obj"), obj_ribbon(16000, True)),
              [sk, "strip", p("usemtl.obj"), "-o", p("o4.obj")], ok))
    e.append((3, "lod build: one usemtl per face, 16k faces", None,
              [sk, "lod", "build", p("usemtl.obj"), "-o", p("o4.sets")], ok))
    e.append((3, "render: one usemtl per face, 16k faces", None,
              [sk, "render", p("usemtl.obj"), "-o", p("o4.png")], ok))
    e.append((3, "lod build: flat ribbon of 32k triangles", lambda: w(p("ribbon.obj"), obj_ribbon(32000, False)),
              [sk, "lod", "build", p("ribbon.obj"), "-o", p("o5.sets")], ok))
    e.append((3, "stats: 32k triangles on one edge", lambda: w(p("book.obj"), obj_book(32000)),
              [sk, "stats", p("book.obj")], ok))
    e.append((3, "stats: 300k identical STL triangles", lambda: w(p("same.stl"), stl_same(300000)),
              [sk, "stats", p("same.stl")], ok))
    e.append((3, "match: path of 100k nodes, weights i mod 7", lambda: w(p("path.dimacs"), dimacs_path(100000, 7)),
              [sk, "match", p("path.dimacs")], (0, 2)))
    e.append((3, "strip: PLY with 50k properties (ASCII)", lambda: w(p("props50k.ply"), ply_props(50000, False)),
              [sk, "strip", p("props50k.ply"), "-o", p("o6.ply")], ok))
    e.append((3, "strip: glb with 20k primitives, --max-memory 1G",
              lambda: w(p("prims20k.glb"), glb_primitives(20000)),
              [sk, "strip", p("prims20k.glb"), "-o", p("o7.glb"), "--max-memory", "1G"], ok))
    e.append((5, "simplify --sequence names the input", None,
              [sk, "simplify", small, "-o", p("o8.obj"), "--ratio", "0.5", "--sequence", small], bad))
    e.append((5, "lod build -o the input", None, [sk, "lod", "build", small, "-o", small], bad))
    e.append((5, "cull --bar the input", None, [sk, "cull", small, "--bar", small], bad))
    reference = {}

    def figure(cmd, key):
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        return json.loads(out)[key]

    def same_pixels(stdout):
        # The unscaled torus is drawn once for comparison.
        if "pixels" not in reference:
            reference["pixels"] = figure([sk, "render", small, "-o", p("o9r.png"), "--json"], "pixels")
        got = json.loads(stdout)["pixels"]
        return abs(got - reference["pixels"]) <= 0.02 * reference["pixels"], f"{got} pixels, unscaled {reference['pixels']}"

    def same_error(stdout):
        # The error relative to the diagonal, scaled and unscaled, and the distance of
        # the scaled result to its input.
        got = json.loads(stdout)
        ref = figure([sk, "simplify", small, "-o", p("o10r.obj"), "--ratio", "0.1", "--json"], "max_error")
        dist = figure([sk, "distance", p("s20.obj"), p("o10.obj"), "--json"], "hausdorff_relative")
        dist_ref = figure([sk, "distance", small, p("o10r.obj"), "--json"], "hausdorff_relative")
        err = got["max_error"]
        fine = math.isfinite(err) and abs(dist - dist_ref) <= 0.01 * dist_ref + 1e-9
        return fine, f"max error {err:.3g} (unscaled {ref:.3g}), distance {dist:.4f} of the diagonal (unscaled {dist_ref:.4f})"

    e.append((6, "render: mesh scaled by 1e18", lambda: scaled_obj(small, 1e18, p("s18.obj")),
              [sk, "render", p("s18.obj"), "-o", p("o9.png"), "--json"], ok, same_pixels))
    e.append((6, "render: mesh scaled by 1e-18", lambda: scaled_obj(small, 1e-18, p("sm18.obj")),
              [sk, "render", p("sm18.obj"), "-o", p("o9m.png"), "--json"], ok, same_pixels))
    e.append((6, "simplify: mesh scaled by 1e20", lambda: scaled_obj(small, 1e20, p("s20.obj")),
              [sk, "simplify", p("s20.obj"), "-o", p("o10.obj"), "--ratio", "0.1", "--json"], ok, same_error))
    e.append((6, "gen -o - | head -c 10", None,
              [sk, "gen", "grid", "300", "300", "-o", "-", "--output-format", "obj"], (1, 2)))
    e.append((6, "Draco block on a primitive (extensionsUsed only)", lambda: w(p("draco.glb"), glb_extension(False, True)),
              [sk, "strip", p("draco.glb"), "-o", p("o11.glb")], bad))
    e.append((7, "OBJ `f 1 1 1` only, -o .glb", lambda: w(p("degen.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 1\n"),
              [sk, "strip", p("degen.obj"), "-o", p("o12.glb")], (0, 2)))
    for cmd in (["stats"], ["strip", "-o", p("o13.glb")], ["strip", "-o", p("o13.ply")]):
        e.append((7, f"unknown extensionsRequired: {cmd[0]} {' '.join(cmd[1:2])} {os.path.splitext(cmd[-1])[1]}",
                  lambda: w(p("req.glb"), glb_extension(True, False)), [sk, cmd[0], p("req.glb")] + cmd[1:], bad))
    e.append((7, "upper-case ASCII STL", lambda: w(p("upper.stl"),
              "SOLID T\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 0 1 0\n"
              "ENDLOOP\nENDFACET\nENDSOLID T\n"), [sk, "stats", p("upper.stl")], ok))
    return e


def main():
    args = sys.argv[1:]
    keep = None
    if "--keep" in args:
        i = args.index("--keep")
        keep = args[i + 1]
        del args[i:i + 2]
    sk = os.path.abspath(args[0] if args else "target/release/stripkit")
    if not os.path.exists(sk):
        sys.exit(f"{sk} not found: build it with `cargo build --release -p stripkit-cli`")
    d = keep or tempfile.mkdtemp(prefix="reproducers30-")
    os.makedirs(d, exist_ok=True)
    rows, missed = [], 0
    try:
        for cls, name, make, cmd, accepted, *check in examples(sk, d):
            if make:
                make()
            if name.startswith("gen -o - | head"):
                code, wall, rss, err = run_piped(cmd, d)
            else:
                code, wall, rss, err = run(cmd, d)
            fine = code in accepted and (rss is None or rss < GIB) and wall < LIMIT_S
            first = err.strip().splitlines()[-1][:90] if err.strip() else ""
            if check and code == 0:
                right, first = check[0](run.stdout)
                fine = fine and right
            missed += not fine
            rows.append((cls, name, code, wall, rss, fine, first))
            mb = f"{rss / 1e6:7.0f}" if rss else "      -"
            print(f"| {cls} | {name} | {code} | {wall:6.2f} | {mb} | {'yes' if fine else 'NO'} | {first} |", flush=True)
    finally:
        if not keep:
            shutil.rmtree(d, ignore_errors=True)
    print(f"{len(rows) - missed} met the targets, {missed} missed")
    sys.exit(1 if missed else 0)


if __name__ == "__main__":
    main()
