"""Dask scaling: a folder of COUNT generated meshes stripped by strip_folder on a
LocalCluster of 1 worker process, then of 2, wall times and the outputs compared byte
for byte (with each other and, when a CLI binary is given, with `stripkit strip`).

    python crates/stripkit-py/bench/dask_scaling.py [COUNT] [GRID] [CLI]
"""

import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import stripkit.dask


def write_grid(path, n, seed):
    rng = np.random.default_rng(seed)
    xs, ys = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
    z = rng.random(xs.size) * 0.3
    with open(path, "w") as f:
        for x, y, h in zip(xs.ravel(), ys.ravel(), z):
            f.write(f"v {x} {y} {h:.5f}\n")
        tris = []
        for y in range(n):
            for x in range(n):
                a = y * (n + 1) + x + 1
                tris += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
        for t in (tris[i] for i in rng.permutation(len(tris))):
            f.write(f"f {t[0]} {t[1]} {t[2]}\n")


def run(src, dst, workers):
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            client.run(lambda: __import__("stripkit"))  # warm imports, not timed
            t = time.perf_counter()
            rows = stripkit.dask.strip_folder(src, dst, client=client)
            return time.perf_counter() - t, rows


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    size = int(sys.argv[2]) if len(sys.argv) > 2 else 120
    cli = sys.argv[3] if len(sys.argv) > 3 else None
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "src")
        os.makedirs(src)
        for i in range(count):
            write_grid(os.path.join(src, f"m{i:03}.obj"), size, i)
        one, rows1 = run(src, os.path.join(tmp, "w1"), 1)
        two, rows2 = run(src, os.path.join(tmp, "w2"), 2)
        assert all(r["error"] is None for r in rows1 + rows2)
        same = all(open(a["output"], "rb").read() == open(b["output"], "rb").read() for a, b in zip(rows1, rows2))
        cli_same = None
        if cli:
            cli_same = True
            for r in rows2:
                out = os.path.join(tmp, "cli.ply")
                subprocess.run([cli, "strip", r["input"], "-o", out], check=True, capture_output=True)
                cli_same &= open(out, "rb").read() == open(r["output"], "rb").read()
        tris = rows1[0]["triangles"]
        print(f"{count} meshes of {tris} triangles: 1 worker {one:.2f} s, 2 workers {two:.2f} s, ratio {two / one:.2f}")
        print(f"outputs identical 1 vs 2 workers: {same}; identical to the CLI's: {cli_same}")


if __name__ == "__main__":
    main()
