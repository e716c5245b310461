"""stripkit.dask on a LocalCluster of 2 worker processes: a folder of generated meshes,
outputs byte-identical to the CLI's, a broken file reported in its row."""

import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import grid, write_obj

distributed = pytest.importorskip("dask.distributed", reason="dask[distributed] is not installed (pip install stripkit[dask])")

import stripkit.dask  # noqa: E402


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    src = tmp_path_factory.mktemp("meshes")
    rng = np.random.default_rng(33)
    for i in range(6):
        vertices, faces = grid(4 + i, 3 + 2 * i, seed=i)
        vertices[:, 2] = rng.random(len(vertices), dtype=np.float32)
        write_obj(src / f"mesh{i:02}.obj", vertices, faces)
    (src / "broken.obj").write_text("v 0 0 0\nf 1 2 3\n")
    (src / "notes.txt").write_text("not a mesh")
    return src


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_strip_folder_matches_the_cli(folder, client, cli, tmp_path):
    dst = tmp_path / "out"
    rows = stripkit.dask.strip_folder(folder, dst, client=client)
    assert [os.path.basename(r["input"]) for r in rows] == ["broken.obj"] + [f"mesh{i:02}.obj" for i in range(6)]
    broken, *good = rows
    assert broken["output"] is None and broken["error"].startswith("ValueError")
    assert "broken.obj" in broken["error"]
    for row in good:
        assert row["error"] is None and row["verified"] is True
        expected = tmp_path / "cli.ply"
        subprocess.run([cli, "strip", row["input"], "-o", str(expected)], check=True, capture_output=True)
        assert open(row["output"], "rb").read() == expected.read_bytes()
        assert row["bytes"] == expected.stat().st_size
    # Atomic writes leave no temporary file behind.
    assert sorted(os.listdir(dst)) == [f"mesh{i:02}.ply" for i in range(6)]
    # Two workers took part.
    assert len(client.scheduler_info()["workers"]) == 2


def test_strip_one_passes_options_and_reports_figures(folder, tmp_path):
    row = stripkit.dask.strip_one(str(folder / "mesh01.obj"), str(tmp_path), "obj", {"algorithm": "cache"})
    assert row["error"] is None and row["output"].endswith("mesh01.obj")
    assert row["triangles"] == 2 * 5 * 5


def test_command_line(folder, tmp_path):
    dst = tmp_path / "cmd"
    run = subprocess.run(
        [sys.executable, "-m", "stripkit.dask", str(folder), str(dst), "--workers", "1"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 1, run.stderr  # broken.obj failed
    assert "6 of 7 files stripped" in run.stdout
    assert "broken.obj" in run.stderr
    assert len(os.listdir(dst)) == 6
