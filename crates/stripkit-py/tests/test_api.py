"""The numpy API: results against the library's rules and the CLI's figures, dtypes and
shapes, every error path, zero copies, the GIL released."""

import json
import os
import subprocess
import sys
import threading

import numpy as np
import pytest

import stripkit
from stripkit import _stripkit
from conftest import ROOT, grid, models_dir, write_obj


def triangle_set(flat):
    """Triangles as a sorted list of rotations starting at their smallest index (winding kept)."""
    out = []
    for a, b, c in np.asarray(flat).reshape(-1, 3).tolist():
        r = [(a, b, c), (b, c, a), (c, a, b)]
        out.append(min(r))
    return sorted(out)


# ---------------------------------------------------------------- stripify on index arrays


def test_stripify_grid_draws_every_triangle_with_its_winding():
    vertices, faces = grid(8, 5, seed=3)
    strip = stripkit.stripify(faces, len(vertices))
    assert strip.dtype == np.uint32 and strip.ndim == 1
    assert len(strip) <= stripkit.stripify_bound(faces.size)
    assert triangle_set(stripkit.unstripify(strip)) == triangle_set(faces)


def test_stripify_degenerate_join_is_one_strip():
    vertices, faces = grid(6, 6, seed=1)
    strip = stripkit.stripify(faces, join="degenerate")
    assert not (strip == stripkit.DEFAULT_RESTART).any()
    assert triangle_set(stripkit.unstripify(strip)) == triangle_set(faces)


@pytest.mark.parametrize("algorithm", ["auto", "greedy", "cache", "balanced", "batch"])
def test_stripify_algorithms_cover_the_triangles(algorithm):
    _, faces = grid(10, 7, seed=5)
    strip = stripkit.stripify(faces, algorithm=algorithm, cache_size=32, restart_index=1000)
    assert triangle_set(stripkit.unstripify(strip, 1000)) == triangle_set(faces)


def test_stripify_matches_the_rust_doc_example():
    # crates/stripkit/src/pipeline/indices.rs: a 2 x 1 quad grid is one strip of 6 indices.
    tris = [0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5]
    assert len(stripkit.stripify(tris, 6)) == 6
    assert stripkit.stripify_bound(12) == 28


@pytest.mark.parametrize("dtype", [np.uint16, np.uint32, np.int32, np.int64, np.uint64, np.uint8])
def test_index_dtypes_give_the_same_strips(dtype):
    _, faces = grid(5, 4, seed=9)
    expected = stripkit.stripify(faces.astype(np.uint32))
    assert np.array_equal(stripkit.stripify(faces.astype(dtype)), expected)
    assert np.array_equal(stripkit.stripify(faces.astype(dtype).ravel()), expected)
    assert np.array_equal(stripkit.stripify(faces.astype(dtype).tolist()), expected)


def test_non_contiguous_input_is_copied_and_gives_the_same_strips():
    _, faces = grid(5, 4, seed=2)
    wide = np.zeros((len(faces), 6), dtype=np.uint32)
    wide[:, ::2] = faces
    view = wide[:, ::2]
    assert not view.flags.c_contiguous
    assert np.array_equal(stripkit.stripify(view), stripkit.stripify(faces))


def test_contiguous_uint32_is_read_in_place():
    _, faces = grid(4, 4)
    for array in (faces, faces.ravel()):
        handed = stripkit._indices(array)
        assert handed.ctypes.data == array.ctypes.data
        assert _stripkit._data_address(handed) == array.ctypes.data
    converted = stripkit._indices(faces.astype(np.int64))
    assert converted.ctypes.data != faces.ctypes.data


def test_acmr_agrees_with_the_figures():
    vertices, faces = grid(9, 9, seed=12)
    # The figures measure the strips in their own order (the restart buffer's).
    strips = stripkit.stripify_mesh(vertices, faces)
    drawn = stripkit.unstripify(strips.indices)
    assert stripkit.acmr(drawn, len(vertices)) == pytest.approx(strips.figures["acmr16"])
    assert stripkit.acmr(drawn, len(vertices), cache_size=32) == pytest.approx(strips.figures["acmr32"])
    with pytest.raises(ValueError, match="between 1 and 65536"):
        stripkit.acmr(drawn, cache_size=0)
    with pytest.raises(ValueError, match="there are 3 vertices"):
        stripkit.acmr([0, 1, 5], 3)
    with pytest.raises(ValueError, match="whole number"):
        stripkit.acmr([0, 1], 3)


# ---------------------------------------------------------------- errors


@pytest.mark.parametrize(
    "indices, kwargs, message",
    [
        ([], {"vertex_count": 3}, "the index list is empty"),
        ([0, 1, 2, 3], {"vertex_count": 4}, "not a whole number of triangles"),
        ([0, 1, 5], {"vertex_count": 4}, "index 2 (triangle 0) is vertex 5 but there are 4 vertices"),
        ([0, 1, 2], {"restart_index": 1}, "restart"),
        ([0, 1, 2], {"algorithm": "fastest"}, "fastest"),
        ([0, 1, 2], {"join": "separate"}, "separate does not fit a flat buffer"),
        ([0, 1, 2], {"algorithm": "single"}, "single may add vertices"),
        ([0, 1, 2], {"cache_size": 0}, "at least 1"),
        ([0, 1, 2], {"cache_size": 70000}, "too large"),
        ([0, 1, 2], {"cache_size": -1}, "negative"),
        ([0, 1, 2], {"restart_index": -1}, "not a 32-bit index"),
        ([0, 1, 2], {"vertex_count": -2}, "negative"),
        ([0, 1, 2], {"vertex_count": 2**40}, "do not fit 32-bit indices"),
        ([0, 1, 2], {"vertex_count": 2**70}, "out of range"),
        ([0, 1, 2], {"cache_size": 2**70}, "out of range"),
        ([0.0, 1.0, 2.0], {}, "integer array"),
        ([True, False, True], {}, "integer array"),
        (np.array([0, -1, 2], dtype=np.int64), {}, "not a 32-bit vertex id"),
        (np.array([0, 1, 2**33], dtype=np.int64), {}, "not a 32-bit vertex id"),
        (np.zeros((2, 4), dtype=np.uint32), {}, "are not triangles"),
        (np.zeros((2, 3, 3), dtype=np.uint32), {}, "3-dimensional"),
        (["a", "b", "c"], {}, "integer array"),
    ],
)
def test_stripify_errors_are_value_errors(indices, kwargs, message):
    with pytest.raises(ValueError) as error:
        stripkit.stripify(indices, **kwargs)
    assert message in str(error.value)


def test_other_errors():
    with pytest.raises(ValueError, match="flat"):
        stripkit.unstripify(np.zeros((2, 2), dtype=np.uint32))
    with pytest.raises(ValueError, match="negative"):
        stripkit.stripify_bound(-1)
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        stripkit.stripify_mesh(np.zeros((4, 2)), [[0, 1, 2]])
    with pytest.raises(ValueError, match="vertex 1 has a NaN"):
        stripkit.stripify_mesh([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(ValueError, match="face 0 refers to vertex 7 but there are 3 vertices"):
        stripkit.stripify_mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 7]])
    with pytest.raises(ValueError, match="real numbers"):
        stripkit.stripify_mesh(np.zeros((3, 3), dtype=complex), [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"\(f, k\)"):
        stripkit.stripify_mesh(np.zeros((3, 3)), [0, 1, 2])
    with pytest.raises(ValueError, match="fastest"):
        stripkit.stripify_mesh(*grid(2, 2), algorithm="fastest")
    with pytest.raises(ValueError, match="restart"):
        stripkit.stripify_mesh(*grid(2, 2), restart_index=3)  # a vertex id of the mesh
    with pytest.raises(ValueError, match="not a mesh format"):
        stripkit.stripify_mesh(*grid(2, 2)).to_bytes("png")
    with pytest.raises(ValueError, match="ratio"):
        stripkit.simplify(stripkit.mesh(*grid(3, 3)), 2.0)
    with pytest.raises(ValueError, match="takes a Mesh"):
        stripkit.simplify(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="takes a Mesh or Strips"):
        stripkit.write("x.ply", 3)
    with pytest.raises(ValueError, match=r"shape \(m, 2\)"):
        stripkit.match(3, [0, 1], [1])
    with pytest.raises(ValueError, match="weights"):
        stripkit.match(2, [[0, 1]], [1, 2])
    with pytest.raises(ValueError, match="integers"):
        stripkit.match(2, [[0, 1]], [1.5])
    with pytest.raises(ValueError):
        stripkit.match(2, [[0, 5]], [1])  # the solver's own message: node out of range
    assert issubclass(stripkit.VerificationError, Exception)
    assert not issubclass(stripkit.VerificationError, ValueError)


def test_file_errors(tmp_path):
    with pytest.raises(OSError):
        stripkit.read(tmp_path / "absent.obj")
    (tmp_path / "mesh.xyz").write_text("")
    with pytest.raises(ValueError, match="unknown mesh format"):
        stripkit.read(tmp_path / "mesh.xyz")
    (tmp_path / "empty.obj").write_text("v 0 0 0\n")
    with pytest.raises(ValueError, match="no faces"):
        stripkit.read(tmp_path / "empty.obj")
    (tmp_path / "bad.obj").write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(ValueError):
        stripkit.read(tmp_path / "bad.obj")
    with pytest.raises(OSError):
        stripkit.write(tmp_path / "no" / "such" / "folder.ply", stripkit.mesh(*grid(1, 1)))


# ---------------------------------------------------------------- meshes, files, figures


def test_stripify_mesh_attributes():
    vertices, faces = grid(6, 4, seed=4)
    strips = stripkit.stripify_mesh(vertices, faces)
    f = strips.figures
    assert f["verified"] is True and f["triangles"] == len(faces)
    assert f["strips"] == len(strips.strips)
    assert len(strips.indices) == f["indices_restart"]
    assert strips.algorithm == "greedy"
    assert strips.vertices.shape == vertices.shape
    drawn = np.concatenate([stripkit.unstripify(s) for s in strips.strips])
    assert triangle_set(drawn) == triangle_set(faces)
    assert "greedy" in repr(strips)


def test_quads_run_qstrip_and_single_adds_no_vertex_on_a_closed_grid():
    vertices, faces = grid(4, 4)
    quads = np.array([[t[0], t[1], t[2], s[2]] for t, s in zip(faces[0::2], faces[1::2])], dtype=np.uint32)
    strips = stripkit.stripify_mesh(vertices, quads)
    assert strips.algorithm == "qstrip" and strips.figures["quads"] == 16 if "quads" in strips.figures else True
    single = stripkit.stripify_mesh(vertices, faces, algorithm="single", join="separate")
    assert single.figures["verified"] is True
    assert len(single.vertices) >= len(vertices)


def test_write_and_read_round_trip(tmp_path):
    vertices, faces = grid(5, 5, seed=8)
    m = stripkit.mesh(vertices, faces)
    stripkit.write(tmp_path / "mesh.ply", m)
    back = stripkit.read(tmp_path / "mesh.ply")
    assert np.array_equal(back.vertices, m.vertices)
    assert np.array_equal(back.triangles, faces)
    strips = stripkit.stripify_mesh(m)
    stripkit.write(tmp_path / "strips.ply", strips)
    assert (tmp_path / "strips.ply").read_bytes() == strips.to_bytes("ply")
    assert "Mesh(36 vertices, 50 faces)" == repr(back)


def test_simplify_returns_the_mesh_and_its_collapses():
    rng = np.random.default_rng(11)
    vertices, faces = grid(12, 12)
    vertices[:, 2] = rng.random(len(vertices), dtype=np.float32) * 0.1
    simplified, collapses, errors = stripkit.simplify(stripkit.mesh(vertices, faces), 0.25)
    assert len(simplified.triangles) <= int(np.ceil(0.25 * len(faces)))
    assert collapses.shape == (len(errors), 2) and collapses.dtype == np.uint32
    used = np.unique(simplified.triangles)
    assert not np.isin(collapses[:, 0], used).any()  # removed vertices are unused
    assert (np.diff(errors) >= -1e-9).all() or len(errors) > 0
    strips = stripkit.stripify_mesh(simplified)
    assert strips.figures["triangles"] == len(simplified.triangles)


def test_match_square():
    # A 4-cycle 0-1-2-3: the heavy perfect matching is {0-1, 2-3} (weight 10 + 10).
    edges = [[0, 1], [1, 2], [2, 3], [3, 0]]
    result = stripkit.match(4, edges, [10, 1, 10, 1])
    assert result["perfect"] and result["total_weight"] == 20
    assert result["edges"].tolist() == [0, 2] and result["mate"].tolist() == [1, 0, 3, 2]
    assert stripkit.match(4, edges, [10, 1, 10, 1], minimize=True)["total_weight"] == 2


def test_trimesh_round_trip():
    trimesh = pytest.importorskip("trimesh", reason="trimesh is not installed (pip install stripkit[trimesh])")
    vertices, faces = grid(3, 3)
    m = stripkit.from_trimesh(trimesh.Trimesh(vertices=vertices, faces=faces, process=False))
    back = stripkit.to_trimesh(stripkit.stripify_mesh(m))
    assert triangle_set(back.faces) == triangle_set(faces)


# ---------------------------------------------------------------- the CLI's figures and bytes


def mesh_inputs():
    paths = sorted(str(p) for p in (ROOT / "assets").glob("*.obj"))
    models = models_dir()
    if models is not None:
        paths += sorted(str(p) for p in models.iterdir() if p.is_file() and p.suffix in (".obj", ".ply", ".off"))
    else:
        print("note: the shared models are absent (set STRIPKIT_MODELS): only assets/ is compared")
    return paths


@pytest.mark.parametrize("path", mesh_inputs(), ids=os.path.basename)
def test_same_bytes_and_figures_as_the_cli(path, cli, tmp_path):
    out = tmp_path / "out.ply"
    run = subprocess.run([cli, "strip", path, "-o", str(out), "--json"], capture_output=True, text=True)
    if run.returncode != 0:
        # The CLI refuses this input: Python must refuse it too, with the same message.
        with pytest.raises((ValueError, OSError)) as error:
            stripkit.strip_file(path)
        assert str(error.value).split(": ")[-1] in run.stderr
        return
    cli_figures = json.loads(run.stdout)
    data, figures = stripkit.strip_file(path)
    assert data == out.read_bytes()
    for key, value in figures.items():
        if key in cli_figures and key != "ms":
            assert cli_figures[key] == value, key
    assert figures["verified"] is True


# ---------------------------------------------------------------- the GIL


def test_gil_is_released_during_stripify_mesh():
    vertices, faces = grid(300, 300, seed=7)
    m = stripkit.mesh(vertices, faces)
    ticks = [0]
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks[0] += 1
            done.wait(0.001)  # blocks without the GIL, then needs it back

    old = sys.getswitchinterval()
    # No forced switches: the counting thread runs only while this thread gives the GIL
    # away, that is inside stripify_mesh if the binding releases it.
    sys.setswitchinterval(100.0)
    thread = threading.Thread(target=count)
    try:
        thread.start()
        before = ticks[0]
        strips = stripkit.stripify_mesh(m, algorithm="cache")
        during = ticks[0] - before
    finally:
        done.set()
        sys.setswitchinterval(old)
        thread.join()
    assert strips.figures["triangles"] == len(faces)
    print(f"the other thread ticked {during} times during stripify_mesh")
    assert during > 0


# ---------------------------------------------------------------- level of detail


def test_lod_levels_draw_at_most_their_triangles(tmp_path):
    rng = np.random.default_rng(21)
    vertices, faces = grid(10, 10, seed=6)
    vertices[:, 2] = rng.random(len(vertices), dtype=np.float32) * 0.2
    lod = stripkit.lod_build(stripkit.mesh(vertices, faces))
    assert lod.levels > 0
    positions, strips, level, triangles = stripkit.lod_extract(lod, level=0)
    assert level == 0 and triangles == len(faces)
    assert triangle_set(np.concatenate([stripkit.unstripify(s) for s in strips])) == triangle_set(faces)
    _, strips, level, triangles = stripkit.lod_extract(lod, ratio=0.5)
    assert triangles <= 100 and sum(len(stripkit.unstripify(s)) for s in strips) == 3 * triangles
    lod.write(str(tmp_path / "grid.sets"))
    again = stripkit.lod_read(tmp_path / "grid.sets")
    assert again.levels == lod.levels
    assert np.array_equal(stripkit.lod_extract(again, triangles=50)[0], stripkit.lod_extract(lod, triangles=50)[0])
    with pytest.raises(ValueError, match="exactly one"):
        stripkit.lod_extract(lod, level=1, ratio=0.5)
    with pytest.raises(ValueError, match="negative"):
        stripkit.lod_extract(lod, level=-1)
    with pytest.raises(ValueError, match="out of range"):
        stripkit.lod_extract(lod, level=10**12)
    with pytest.raises(ValueError):
        stripkit.lod_read(__file__)  # not a model: the library's format error
    with pytest.raises(OSError):
        stripkit.lod_read(tmp_path / "absent.sets")
