"""Python call overhead over the Rust library, in one run: the library's own timing of
`stripify` (mesh as read) and `stripify_indices` (its triangles) from the Rust example
`stripify_time`, then the same calls through the Python package, medians of RUNS calls
each, alternated ROUNDS times so that both see the same machine load.

    cargo build --release -p stripkit --example stripify_time
    python crates/stripkit-py/bench/overhead.py MESH [RUNS] [ROUNDS]
"""

import json
import pathlib
import statistics
import subprocess
import sys
import time

import numpy as np

import stripkit

ROOT = pathlib.Path(__file__).resolve().parents[3]


def median_ms(runs, f):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        times.append((time.perf_counter() - t) * 1e3)
    return statistics.median(times)


def main():
    path = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 15
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    example = ROOT / "target/release/examples/stripify_time"
    mesh = stripkit.read(path)
    tris = np.ascontiguousarray(mesh.triangles)
    n = len(mesh.vertices)
    rust_mesh, rust_idx, py_mesh, py_idx = [], [], [], []
    for _ in range(rounds):
        out = json.loads(subprocess.run([str(example), path, str(runs)], check=True, capture_output=True, text=True).stdout)
        rust_mesh.append(out["stripify_mesh_ms"])
        rust_idx.append(out["stripify_indices_ms"])
        py_mesh.append(median_ms(runs, lambda: stripkit.stripify_mesh(mesh)))
        py_idx.append(median_ms(runs, lambda: stripkit.stripify(tris, n)))
    rm, ri, pm, pi = (statistics.median(x) for x in (rust_mesh, rust_idx, py_mesh, py_idx))
    print(f"{path}: {len(tris)} triangles, median of {rounds} rounds x {runs} calls")
    print(f"stripify_mesh: Rust {rm:.2f} ms, Python {pm:.2f} ms, overhead {100 * (pm / rm - 1):+.1f}%")
    print(f"stripify (indices): Rust {ri:.2f} ms, Python {pi:.2f} ms, overhead {100 * (pi / ri - 1):+.1f}%")


if __name__ == "__main__":
    main()
