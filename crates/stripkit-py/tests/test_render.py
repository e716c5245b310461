"""stripkit.render: the same pixels as `stripkit render`, bad arguments refused. The
pictures need EGL; where it is absent those tests skip, saying so."""

import os
import struct
import subprocess
import sys
import threading
import time
import zlib

import numpy as np
import pytest

import stripkit
from conftest import grid, models_dir, write_obj


def read_png_rgb(path):
    """An 8-bit RGB PNG (what the CLI writes) as an (h, w, 3) uint8 array: zlib and the
    five row filters, nothing more."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack(">IIBB", body[:10])
            assert (depth, color) == (8, 2), "an 8-bit RGB picture"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride, bpp = width * 3, 3
    out = np.zeros((height, stride), dtype=np.uint8)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, dtype=np.int32)
        for x in range(stride):
            a = cur[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 0xFF
        out[y] = cur
        prev = cur
    return out.reshape(height, width, 3)


def bumpy(nx, ny, seed):
    """A shuffled grid with a bump, so that shading and framing have depth to show."""
    vertices, faces = grid(nx, ny, seed=seed)
    vertices[:, 2] = np.sin(vertices[:, 0] * 0.7) * np.cos(vertices[:, 1] * 0.5) * 1.5
    return vertices, faces


def egl_or_skip():
    v, f = grid(1, 1)
    try:
        stripkit.render(v, f, width=16, height=16)
    except OSError as e:
        print(f"skipped: no EGL on this machine ({e})")
        pytest.skip(f"no EGL on this machine ({e})")


CASES = [
    ([], {}),
    (["--color", "order", "--shading", "smooth", "--size", "96x64"], dict(color_by="order", shading="smooth", width=96, height=64)),
    (["--color", "cull", "--cull-view", "0,0,-1", "--view", "1,0.5,0.2", "--wireframe", "--size", "120x90"],
     dict(color_by="cull", cull_view=(0, 0, -1), view=(1, 0.5, 0.2), wireframe=True, width=120, height=90)),
    (["--color", "none", "--shading", "unlit", "--zoom", "2", "--fov", "45", "--background", "10,20,30", "--up", "0,0,1"],
     dict(color_by="none", shading="unlit", zoom=2, fov=45, background=(10, 20, 30), up=(0, 0, 1))),
]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_render_matches_the_cli_pixel_for_pixel(case, cli, tmp_path):
    egl_or_skip()
    flags, kwargs = CASES[case]
    kwargs.setdefault("width", 80)
    kwargs.setdefault("height", 80)
    if "--size" not in flags:
        flags = flags + ["--size", "80x80"]
    vertices, faces = bumpy(12, 9, seed=case)
    obj = tmp_path / "bumpy.obj"
    write_obj(obj, vertices, faces)
    png = tmp_path / "cli.png"
    run = subprocess.run([cli, "render", str(obj), "-o", str(png)] + flags, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    expected = read_png_rgb(png)

    strips = stripkit.stripify_mesh(stripkit.read(obj))
    picture = stripkit.render(strips.vertices, strips, **kwargs)
    assert picture.dtype == np.uint8 and picture.shape == expected.shape
    assert np.array_equal(picture, expected), f"{int((picture != expected).any(axis=2).sum())} pixels differ"
    background = np.array(kwargs.get("background", (255, 255, 255)), dtype=np.uint8)
    drawn = int((picture != background).any(axis=2).sum())
    assert drawn > picture.shape[0] * picture.shape[1] // 20, drawn  # side views fill less
    # The same strips as a joined buffer, and as RGBA.
    rgba = stripkit.render(strips.vertices, strips.indices, alpha=True, **kwargs)
    assert rgba.shape == expected.shape[:2] + (4,) and np.array_equal(rgba[:, :, :3], expected)
    assert (rgba[:, :, 3] == 255).all()


@pytest.mark.parametrize("name, algo, flags, kwargs", [
    ("bunny.obj", "auto", [], {}),
    ("bunny.obj", "single", ["--wireframe", "--color", "order"], dict(wireframe=True, color_by="order")),
    ("cow.obj", "auto", ["--shading", "smooth"], dict(shading="smooth")),
])
def test_shared_meshes_match_the_cli(name, algo, flags, kwargs, cli, tmp_path):
    models = models_dir()
    if models is None or not (models / name).is_file():
        print(f"skipped: {name} is absent (set STRIPKIT_MODELS)")
        pytest.skip(f"{name} is absent (set STRIPKIT_MODELS)")
    egl_or_skip()
    path = str(models / name)
    png = tmp_path / "cli.png"
    run = subprocess.run([cli, "render", path, "-o", str(png), "--algo", algo, "--size", "400x300"] + flags,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    expected = read_png_rgb(png)
    strips = stripkit.stripify_mesh(stripkit.read(path), algorithm=algo)
    picture = stripkit.render(strips.vertices, strips, width=400, height=300, **kwargs)
    assert np.array_equal(picture, expected), f"{int((picture != expected).any(axis=2).sum())} pixels differ"


def test_a_triangle_list_draws_every_face():
    egl_or_skip()
    vertices, faces = bumpy(6, 6, seed=3)
    picture = stripkit.render(vertices, faces, width=64, height=48, color_by="none", shading="unlit")
    assert picture.shape == (48, 64, 3)
    grey = (picture == np.array([205, 205, 205], dtype=np.uint8)).all(axis=2)
    assert grey.sum() > 64 * 48 // 4, int(grey.sum())


def test_bad_arguments_raise_value_error():
    v, f = grid(2, 2)
    bad = [
        dict(width=8),
        dict(height=5000),
        dict(width=80.5),
        dict(color_by="rainbow"),
        dict(shading="phong"),
        dict(view=(0, 0, 0)),
        dict(view=(1, 2)),
        dict(up=(0, 0, 2), view=(0, 0, 1)),
        dict(fov=170),
        dict(zoom=0.5),
        dict(background=(256, 0, 0)),
        dict(cull_view=(1, 0, 0)),
        dict(color_by="cull", cull_view=(0, 0, 0)),
    ]
    for kwargs in bad:
        with pytest.raises(ValueError):
            stripkit.render(v, f, **kwargs)
    with pytest.raises(ValueError, match="refers past"):
        stripkit.render(v, np.array([[0, 1, 99]]))
    with pytest.raises(ValueError, match="shape"):
        stripkit.render(v[:, :2], f)
    with pytest.raises(ValueError):
        stripkit.render(v, np.zeros((2, 2, 3), dtype=np.uint32))
    with pytest.raises(ValueError):
        stripkit.render(v, [np.array([0, 1, -2])])


def test_no_faces_is_a_value_error_not_a_crash():
    egl_or_skip()
    v, _ = grid(1, 1)
    with pytest.raises(ValueError, match="no faces|nothing to frame"):
        stripkit.render(v, np.array([[0, 0, 1]], dtype=np.uint32))


def test_without_egl_the_package_imports_and_render_says_what_to_install():
    # A fresh interpreter whose EGL library is missing: importing works, render raises.
    code = (
        "import stripkit, numpy as np\n"
        "v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)\n"
        "try:\n"
        "    stripkit.render(v, np.array([[0, 1, 2]]), width=16, height=16)\n"
        "except OSError as e:\n"
        "    print('OSError:', e)\n"
    )
    env = dict(os.environ, STRIPKIT_EGL_LIBRARY="/nonexistent/libEGL.so.1")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    for words in ["OSError:", "/nonexistent/libEGL.so.1", "apt-get install libegl1"]:
        assert words in run.stdout, run.stdout


def test_render_releases_the_gil():
    egl_or_skip()
    vertices, faces = bumpy(200, 200, seed=5)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    thread = threading.Thread(target=count)
    thread.start()
    try:
        before = len(ticks)
        stripkit.render(vertices, faces, width=512, height=512, wireframe=True)
        during = len(ticks) - before
    finally:
        done.set()
        thread.join()
    assert during > 0, "the other thread made no progress while render ran"
