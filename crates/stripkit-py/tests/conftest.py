"""Shared fixtures: procedural meshes, the CLI binary, the model folder."""

import os
import pathlib
import shutil

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


def grid(nx, ny, seed=None):
    """An nx x ny grid of quads as triangles, (vertices, faces); faces shuffled when seeded."""
    xs, ys = np.meshgrid(np.arange(nx + 1, dtype=np.float32), np.arange(ny + 1, dtype=np.float32))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size, np.float32)], axis=1)
    tris = []
    for y in range(ny):
        for x in range(nx):
            a = y * (nx + 1) + x
            b, c, d = a + 1, a + nx + 1, a + nx + 2
            tris += [[a, b, d], [a, d, c]]
    faces = np.array(tris, dtype=np.uint32)
    if seed is not None:
        faces = faces[np.random.default_rng(seed).permutation(len(faces))]
    return vertices, faces


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        for v in vertices:
            f.write(f"v {v[0]:.6f} {v[1]:.6f} {v[2]:.6f}\n")
        for t in faces:
            f.write("f " + " ".join(str(int(i) + 1) for i in t) + "\n")


@pytest.fixture(scope="session")
def cli():
    """The `stripkit` binary: $STRIPKIT_CLI, else target/{release,debug}/stripkit."""
    for candidate in (os.environ.get("STRIPKIT_CLI"), ROOT / "target/release/stripkit", ROOT / "target/debug/stripkit"):
        if candidate and os.path.isfile(candidate):
            return str(candidate)
    found = shutil.which("stripkit")
    if found:
        return found
    pytest.skip("the stripkit CLI is not built (cargo build -p stripkit-cli, or set STRIPKIT_CLI)")


def models_dir():
    """The research meshes: $STRIPKIT_MODELS, else ../shared/models beside the checkout."""
    for candidate in (os.environ.get("STRIPKIT_MODELS"), ROOT.parent / "shared/models"):
        if candidate and os.path.isdir(candidate):
            return pathlib.Path(candidate)
    return None
