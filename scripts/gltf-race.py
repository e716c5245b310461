#!/usr/bin/env python3
"""Race reproducer for external glTF buffers (issue #30, class 4).

An asset folder holds `scene.gltf`, whose buffer is `sub/mesh.bin` (one triangle);
an outside folder holds a secret buffer of the same size whose triangle is degenerate
(three equal corners). A thread swaps `sub/` for a symbolic link to the outside folder and back
(renameat2 RENAME_EXCHANGE, atomic) in a tight loop while the CLI reads the asset
RUNS times with `stats --json`. A read that counts a degenerate face read outside
the asset's folder.

Usage: gltf-race.py STRIPKIT [RUNS]   (Linux; prints counts of each outcome)
"""
import ctypes, json, os, struct, subprocess, sys, tempfile, threading

AT_FDCWD, RENAME_EXCHANGE = -100, 2
libc = ctypes.CDLL(None, use_errno=True)


def exchange(a, b):
    if libc.renameat2(AT_FDCWD, a.encode(), AT_FDCWD, b.encode(), RENAME_EXCHANGE) != 0:
        raise OSError(ctypes.get_errno(), "renameat2")


def triangle(size):
    return struct.pack("<9f", 0, 0, 0, size, 0, 0, 0, size, 0)


def main():
    exe, runs = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    root = tempfile.mkdtemp(prefix="gltf-race-")
    asset, outside = os.path.join(root, "asset"), os.path.join(root, "outside")
    os.makedirs(os.path.join(asset, "sub"))
    os.makedirs(outside)
    with open(os.path.join(asset, "sub", "mesh.bin"), "wb") as f:
        f.write(triangle(1.0))
    with open(os.path.join(outside, "mesh.bin"), "wb") as f:
        f.write(triangle(0.0))
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "sub/mesh.bin", "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    }
    gltf = os.path.join(asset, "scene.gltf")
    with open(gltf, "w") as f:
        json.dump(doc, f)
    # `link` is the symbolic link to the outside folder that trades places with sub/.
    sub, link = os.path.join(asset, "sub"), os.path.join(asset, "link")
    os.symlink(outside, link)
    stop = threading.Event()

    def swap():
        while not stop.is_set():
            exchange(sub, link)

    t = threading.Thread(target=swap, daemon=True)
    t.start()
    counts = {"inside": 0, "outside": 0, "refused": 0, "other": 0}
    try:
        for _ in range(runs):
            r = subprocess.run([exe, "stats", gltf, "--json"], capture_output=True, text=True)
            if r.returncode == 0:
                counts["outside" if '"degenerate_faces": 1' in r.stdout else "inside"] += 1
            elif r.returncode == 2:
                counts["refused"] += 1
            else:
                counts["other"] += 1
                sys.stderr.write(r.stderr)
    finally:
        stop.set()
        t.join()
    print(" ".join(f"{k}={v}" for k, v in counts.items()), f"runs={runs}")


if __name__ == "__main__":
    main()
