"""Triangle strips on numpy arrays: stripkit's library from Python.

Every function is a thin wrapper over one entry point of the Rust library: inputs are
checked here (dtype, shape, index range, NaN) and handed over as contiguous ``uint32`` /
``float32`` arrays, read in place without a copy; the work runs with the GIL released,
so Python threads run in parallel; every strip output is verified by the library.

Errors: ``ValueError`` for input the library refuses (its message), ``VerificationError``
when an output fails its check, ``OSError`` for files.

>>> import numpy as np, stripkit
>>> tris = np.array([[0, 3, 1], [1, 3, 4], [1, 4, 2], [2, 4, 5]], dtype=np.uint32)
>>> strip = stripkit.stripify(tris, 6)
>>> len(strip)
6
>>> stripkit.unstripify(strip).reshape(-1, 3).shape
(4, 3)
"""

from __future__ import annotations

import functools
import json
import os
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _stripkit
from ._stripkit import DEFAULT_RESTART, Lod, Mesh, VerificationError

__all__ = [
    "DEFAULT_RESTART",
    "acmr",
    "Lod",
    "Mesh",
    "Strips",
    "VerificationError",
    "from_trimesh",
    "lod_build",
    "lod_extract",
    "lod_read",
    "match",
    "mesh",
    "read",
    "render",
    "simplify",
    "strip_file",
    "stripify",
    "stripify_bound",
    "stripify_mesh",
    "to_trimesh",
    "unstripify",
    "write",
]

def _checked(function: Any) -> Any:
    """A Python integer too large for the library's argument (e.g. ``cache_size=2**70``)
    is a ``ValueError`` like every other bad input, not PyO3's ``OverflowError``."""

    @functools.wraps(function)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return function(*args, **kwargs)
        except OverflowError as e:
            raise ValueError(f"{function.__name__}: an argument is out of range ({e})") from None

    return wrapper


_INDEX_DTYPES = (np.uint8, np.uint16, np.uint32, np.uint64, np.int8, np.int16, np.int32, np.int64)


def _as_u32(array: Any, what: str) -> np.ndarray:
    """``array`` as a flat contiguous uint32 array: the same buffer when it already is
    one (or a contiguous (n, k) one), else a checked conversion."""
    a = np.asarray(array)
    if a.size == 0:
        return np.zeros(0, dtype=np.uint32)  # `[]` is float64 to numpy: nothing to check
    if a.dtype == np.uint32 and a.flags.c_contiguous:
        return a.reshape(-1)
    if a.dtype == np.bool_ or not any(a.dtype == t for t in _INDEX_DTYPES):
        raise ValueError(f"{what} must be an integer array (uint16, uint32, int64, ...), not {a.dtype}")
    if a.size and (int(a.min()) < 0 or int(a.max()) > 0xFFFFFFFF):
        bad = int(a.min()) if int(a.min()) < 0 else int(a.max())
        raise ValueError(f"{what} holds {bad}, which is not a 32-bit vertex id")
    return np.ascontiguousarray(a, dtype=np.uint32).reshape(-1)


def _indices(indices: Any) -> np.ndarray:
    a = np.asarray(indices)
    if a.ndim == 2 and a.shape[1] != 3:
        raise ValueError(f"indices of shape {a.shape} are not triangles: use (n, 3) or a flat array")
    if a.ndim not in (1, 2):
        raise ValueError(f"indices must be flat or (n, 3), not {a.ndim}-dimensional")
    return _as_u32(a, "indices")


def _vertices(vertices: Any) -> np.ndarray:
    v = np.asarray(vertices)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), not {v.shape}")
    if not np.issubdtype(v.dtype, np.number) or np.issubdtype(v.dtype, np.complexfloating):
        raise ValueError(f"vertices must be real numbers, not {v.dtype}")
    v = np.ascontiguousarray(v, dtype=np.float32)
    if not np.isfinite(v).all():
        row = int(np.argwhere(~np.isfinite(v))[0][0])
        raise ValueError(f"vertex {row} has a NaN or infinite coordinate")
    return v


@_checked
def stripify(
    indices: Any,
    vertex_count: Optional[int] = None,
    *,
    algorithm: str = "auto",
    restart_index: int = DEFAULT_RESTART,
    cache_size: int = 16,
    join: str = "restart",
) -> np.ndarray:
    """Strips for a triangle list (meshoptimizer's shape): one uint32 buffer of strips
    separated by ``restart_index`` (``join="restart"``) or one stitched strip
    (``join="degenerate"``), verified, at most ``stripify_bound(len(indices))`` long.

    ``indices``: (n, 3) or flat, any integer dtype (checked, converted; contiguous uint32
    is read in place). ``vertex_count``: default the largest index plus one.
    ``algorithm``: auto, greedy, qstrip, cache, balanced or batch.
    """
    flat = _indices(indices)
    if vertex_count is None:
        vertex_count = int(flat.max()) + 1 if flat.size else 0
    if vertex_count < 0:
        raise ValueError(f"vertex_count {vertex_count} is negative")
    return _stripkit.stripify_indices(flat, vertex_count, algorithm, _restart(restart_index), _cache(cache_size), join)


def _restart(value: int) -> int:
    if not 0 <= int(value) <= 0xFFFFFFFF:
        raise ValueError(f"restart_index {value} is not a 32-bit index")
    return int(value)


def _cache(value: int) -> int:
    if int(value) < 0:
        raise ValueError(f"cache_size {value} is negative")
    return int(value)


@_checked
def stripify_bound(index_count: int) -> int:
    """The most indices :func:`stripify` returns for ``index_count`` input indices."""
    if int(index_count) < 0:
        raise ValueError(f"index_count {index_count} is negative")
    return _stripkit.stripify_bound(int(index_count))


@_checked
def acmr(indices: Any, vertex_count: Optional[int] = None, *, cache_size: int = 16) -> float:
    """Vertex-cache misses per triangle (a FIFO of ``cache_size`` entries) of a triangle
    list drawn in order: the figure ``Strips.figures["acmr"]`` gives for strips, here for
    any list (e.g. ``unstripify(strip)`` or another library's reordered indices)."""
    flat = _indices(indices)
    if vertex_count is None:
        vertex_count = int(flat.max()) + 1 if flat.size else 0
    if vertex_count < 0:
        raise ValueError(f"vertex_count {vertex_count} is negative")
    return _stripkit.acmr(flat, vertex_count, _cache(cache_size))


@_checked
def unstripify(strip: Any, restart_index: int = DEFAULT_RESTART) -> np.ndarray:
    """The triangle list (flat uint32, three per triangle) a strip buffer draws, winding
    kept, degenerate triangles dropped; ``restart_index`` separates strips."""
    a = np.asarray(strip)
    if a.ndim != 1:
        raise ValueError(f"a strip buffer is flat, not of shape {a.shape}")
    return _stripkit.unstripify(_as_u32(a, "strip"), _restart(restart_index))


@_checked
def mesh(vertices: Any, faces: Any) -> Mesh:
    """A :class:`Mesh` from vertices (n, 3) and faces (f, k): triangles (k = 3), quads
    (k = 4) or any polygons of k vertices; indices checked against n."""
    v = _vertices(vertices)
    f = np.asarray(faces)
    if f.ndim != 2 or f.shape[1] < 3:
        raise ValueError(f"faces must have shape (f, k) with k >= 3, not {f.shape}")
    flat = _as_u32(f, "faces")
    if flat.size and int(flat.max()) >= len(v):
        i = int(np.argmax(flat >= len(v)))
        raise ValueError(f"face {i // f.shape[1]} refers to vertex {int(flat[i])} but there are {len(v)} vertices")
    return _stripkit.mesh_from_arrays(v, flat, int(f.shape[1]))


class Strips:
    """Verified strips of a mesh: ``.indices`` (the joined buffer), ``.strips`` (one
    uint32 array per strip), ``.figures`` (every figure of docs/metrics.md, a dict),
    ``.vertices`` (the positions indexed, with any ``single`` added), ``.algorithm``."""

    def __init__(self, inner: Any) -> None:
        self._inner = inner
        self.figures: Dict[str, Any] = json.loads(inner._figures_json())

    @property
    def indices(self) -> np.ndarray:
        return self._inner.indices

    @property
    def strips(self) -> List[np.ndarray]:
        return self._inner.strips

    @property
    def vertices(self) -> np.ndarray:
        return self._inner.vertices

    @property
    def algorithm(self) -> str:
        return self._inner.algorithm

    def to_bytes(self, format: str = "ply", *, ascii: bool = False) -> bytes:
        """The file bytes ``stripkit strip`` writes for these strips (ply, obj, gltf, glb)."""
        return self._inner.to_bytes(format, ascii)

    def __repr__(self) -> str:
        f = self.figures
        return f"Strips({self.algorithm}: {f['strips']} strips, {f['triangles']} triangles, acmr {f['acmr']:.3f})"


@_checked
def stripify_mesh(
    vertices: Any,
    faces: Any = None,
    *,
    algorithm: str = "auto",
    restart_index: int = DEFAULT_RESTART,
    cache_size: int = 16,
    join: str = "restart",
    weld: bool = True,
) -> Strips:
    """Strips for a mesh (the library's front door): ``vertices`` (n, 3) and ``faces``
    (f, k), or a :class:`Mesh` alone. Chooses the algorithm ("auto": QSTRIP on
    quad-dominant meshes, greedy otherwise), runs it, verifies and measures."""
    m = vertices if isinstance(vertices, Mesh) else mesh(vertices, faces)
    inner = _stripkit.stripify_mesh(m, algorithm, _restart(restart_index), _cache(cache_size), join, bool(weld))
    result = Strips(inner)
    result._mesh = m
    result._restart = _restart(restart_index)
    return result


_COLOR_BY = ("strips", "order", "cull", "none")
_SHADINGS = ("flat", "smooth", "unlit")


def _direction(value: Any, what: str) -> Tuple[float, float, float]:
    d = np.asarray(value, dtype=np.float64) if not isinstance(value, str) else np.zeros(0)
    if d.shape != (3,) or not np.isfinite(d).all():
        raise ValueError(f"{what} must be three finite numbers (x, y, z), not {value!r}")
    if not d.any():
        raise ValueError(f"{what} must not be 0,0,0")
    return (float(d[0]), float(d[1]), float(d[2]))


def _render_buffer(strips_or_indices: Any, restart: int) -> Tuple[np.ndarray, bool]:
    """The strips as one restart-separated uint32 buffer, or a flat triangle list
    (the flag says which)."""
    if isinstance(strips_or_indices, Strips):
        strips_or_indices = strips_or_indices.strips
    if isinstance(strips_or_indices, (list, tuple)):
        parts: List[np.ndarray] = []
        for k, s in enumerate(strips_or_indices):
            a = np.asarray(s)
            if a.ndim != 1:
                raise ValueError(f"strip {k} must be flat, not of shape {a.shape}")
            if parts:
                parts.append(np.array([restart], dtype=np.uint32))
            parts.append(_as_u32(a, f"strip {k}"))
        return (np.concatenate(parts) if parts else np.zeros(0, np.uint32)), False
    a = np.asarray(strips_or_indices)
    if a.ndim == 2:
        return _indices(a), True
    if a.ndim != 1:
        raise ValueError(f"strips_or_indices must be a strip buffer, a list of strips or (n, 3) triangles, not {a.shape}")
    return _as_u32(a, "strip buffer"), False


@_checked
def render(
    vertices: Any,
    strips_or_indices: Any,
    *,
    width: int = 800,
    height: int = 800,
    color_by: str = "strips",
    wireframe: bool = False,
    shading: str = "flat",
    view: Any = (0.3, 0.4, 1.0),
    up: Any = (0.0, 1.0, 0.0),
    fov: float = 30.0,
    zoom: float = 1.0,
    background: Any = (255, 255, 255),
    cull_view: Any = None,
    restart_index: int = DEFAULT_RESTART,
    alpha: bool = False,
) -> np.ndarray:
    """The picture ``stripkit render`` draws, as a (height, width, 3) uint8 array
    (RGB, top row first; (height, width, 4) RGBA with ``alpha=True``).

    ``strips_or_indices``: a :class:`Strips`, a list of strips (1-D index arrays), a
    strip buffer (1-D, strips separated by ``restart_index``), or an (n, 3) triangle
    list (drawn as one strip). ``vertices`` (n, 3): those the strips index (with any
    ``single`` added: ``Strips.vertices``). ``color_by``: "strips", "order", "cull"
    (facing an eye in ``cull_view``, default ``view``) or "none"; ``shading``: "flat",
    "smooth" or "unlit"; ``width`` / ``height`` 16 to 4096; ``fov`` 1 to 120 degrees;
    ``zoom`` 1 to 100; ``background`` (r, g, b) 0 to 255. The same pixels as the CLI
    with the same input and options.

    Needs EGL and OpenGL ES 3 at run time: without them an ``OSError`` says what to
    install (Debian, Ubuntu: libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri). The GIL
    is released while drawing."""
    v = _vertices(vertices)
    restart = _restart(restart_index)
    buffer, triangle_list = _render_buffer(strips_or_indices, restart)
    if triangle_list and buffer.size % 3:
        raise ValueError("a triangle list needs three indices per triangle")
    used = buffer if triangle_list else buffer[buffer != restart]
    if used.size and int(used.max()) >= len(v):
        raise ValueError(f"index {int(used.max())} refers past the {len(v)} vertices")
    for name, side in (("width", width), ("height", height)):
        if isinstance(side, bool) or not isinstance(side, (int, np.integer)) or not 16 <= side <= 4096:
            raise ValueError(f"{name} must be an integer from 16 to 4096, not {side!r}")
    if color_by not in _COLOR_BY:
        raise ValueError(f"color_by must be one of {', '.join(_COLOR_BY)}, not {color_by!r}")
    if shading not in _SHADINGS:
        raise ValueError(f"shading must be one of {', '.join(_SHADINGS)}, not {shading!r}")
    if cull_view is not None and color_by != "cull":
        raise ValueError('cull_view applies to color_by="cull"')
    if not 1.0 <= float(fov) <= 120.0:
        raise ValueError(f"fov must be from 1 to 120 degrees, not {fov!r}")
    if not 1.0 <= float(zoom) <= 100.0:
        raise ValueError(f"zoom must be from 1 to 100, not {zoom!r}")
    bg = np.asarray(background)
    if bg.shape != (3,) or not np.issubdtype(bg.dtype, np.integer) or (bg < 0).any() or (bg > 255).any():
        raise ValueError(f"background must be three integers from 0 to 255, not {background!r}")
    image = _stripkit.render(
        v,
        buffer,
        restart,
        triangle_list,
        (int(width), int(height)),
        color_by,
        None if cull_view is None else _direction(cull_view, "cull_view"),
        shading,
        bool(wireframe),
        _direction(view, "view"),
        _direction(up, "up"),
        float(fov),
        float(zoom),
        tuple(int(c) for c in bg),
    )
    return image if alpha else np.ascontiguousarray(image[:, :, :3])


def read(path: "os.PathLike[str] | str") -> Mesh:
    """Reads a mesh (OBJ, PLY, OFF, STL, glTF/GLB, optionally .gz)."""
    return _stripkit.read(os.fspath(path))


def write(path: "os.PathLike[str] | str", mesh_or_strips: "Mesh | Strips", *, ascii: bool = False) -> None:
    """Writes a mesh, or strips (with their mesh) where the format holds strips (PLY
    tristrips, glTF TRIANGLE_STRIP); the file is replaced atomically."""
    if isinstance(mesh_or_strips, Strips):
        _stripkit.write(os.fspath(path), mesh_or_strips._mesh, mesh_or_strips._inner, ascii)
    elif isinstance(mesh_or_strips, Mesh):
        _stripkit.write(os.fspath(path), mesh_or_strips, None, ascii)
    else:
        raise ValueError(f"write takes a Mesh or Strips, not {type(mesh_or_strips).__name__}")


def strip_file(src: "os.PathLike[str] | str", format: str = "ply", **options: Any) -> Tuple[bytes, Dict[str, Any]]:
    """Reads ``src``, strips it (keyword options as :func:`stripify_mesh`) and returns
    the output file's bytes (those of ``stripkit strip SRC OUT.<format>`` for ply and
    obj) and the figures."""
    strips = stripify_mesh(read(src), **options)
    return strips.to_bytes(format), strips.figures


@_checked
def simplify(m: Mesh, ratio: float = 0.5, *, triangles: Optional[int] = None) -> Tuple[Mesh, np.ndarray, np.ndarray]:
    """Quadric edge collapse to ``ratio`` of the triangles (or ``triangles`` of them).
    Returns the simplified mesh (all input vertices kept, removed ones unused), the
    collapses as (c, 2) uint32 rows (removed, kept) in order, and their errors."""
    if not isinstance(m, Mesh):
        raise ValueError(f"simplify takes a Mesh (stripkit.mesh or stripkit.read), not {type(m).__name__}")
    if triangles is not None and int(triangles) < 0:
        raise ValueError(f"triangles {triangles} is negative")
    return _stripkit.simplify(m, float(ratio), None if triangles is None else int(triangles))


@_checked
def match(node_count: int, edges: Any, weights: Any, *, minimize: bool = False) -> Dict[str, Any]:
    """A perfect matching of maximum weight (``minimize``: minimum cost) on a graph
    given as an (m, 2) edge list and m integer weights; without a perfect matching, a
    maximum one. Returns ``mate`` (partner of each node, 0xFFFFFFFF unmatched),
    ``edges`` (matched edge ids), ``perfect`` and ``total_weight``."""
    e = np.asarray(edges)
    if e.ndim != 2 or e.shape[1] != 2:
        raise ValueError(f"edges must have shape (m, 2), not {e.shape}")
    w = np.asarray(weights)
    if w.shape != (e.shape[0],):
        raise ValueError(f"{e.shape[0]} edges need {e.shape[0]} weights, not shape {w.shape}")
    if not np.issubdtype(w.dtype, np.integer):
        raise ValueError(f"weights must be integers, not {w.dtype}")
    if int(node_count) < 0:
        raise ValueError(f"node_count {node_count} is negative")
    mate, matched, perfect, total = _stripkit.match_edges(
        int(node_count), _as_u32(e, "edges"), np.ascontiguousarray(w, dtype=np.int64), bool(minimize)
    )
    return {"mate": mate, "edges": matched, "perfect": perfect, "total_weight": total}


@_checked
def lod_build(m: Mesh, *, algorithm: str = "auto", cache_size: int = 16) -> Lod:
    """A multiresolution strip model (SETS) of ``m``: strips, simplified as far as the
    simplifier goes, every level checked against a replay; a level whose strips pass
    1.6 indices per triangle gets new strips (``stripkit lod build``'s default
    ``--restrip 1.6``). ``lod.levels`` is its last level; ``lod.write(path)`` stores it as ``.sets``."""
    if not isinstance(m, Mesh):
        raise ValueError(f"lod_build takes a Mesh (stripkit.mesh or stripkit.read), not {type(m).__name__}")
    return _stripkit.lod_build(m, algorithm, _cache(cache_size))


def lod_read(path: "os.PathLike[str] | str") -> Lod:
    """Reads a ``.sets`` or ``.lodseq`` model."""
    return _stripkit.lod_read(os.fspath(path))


@_checked
def lod_extract(
    lod: Lod,
    *,
    level: Optional[int] = None,
    triangles: Optional[int] = None,
    ratio: Optional[float] = None,
    frame: Optional[float] = None,
) -> Tuple[np.ndarray, List[np.ndarray], int, int]:
    """One level of ``lod``, named by exactly one of ``level`` (collapses applied),
    ``triangles`` (the first level with at most that many) or ``ratio``: returns
    (positions (n, 3) float32, strips as uint32 arrays, level, triangles)."""
    given = [(k, v) for k, v in (("level", level), ("triangles", triangles), ("ratio", ratio)) if v is not None]
    if len(given) != 1:
        raise ValueError("name the level by exactly one of level=, triangles= or ratio=")
    kind, value = given[0]
    if kind != "ratio" and int(value) < 0:
        raise ValueError(f"{kind} {value} is negative")
    return lod.extract(kind, float(value), None if frame is None else float(frame))


def from_trimesh(tm: Any) -> Mesh:
    """A :class:`Mesh` from a ``trimesh.Trimesh`` (its vertices and faces)."""
    return mesh(np.asarray(tm.vertices), np.asarray(tm.faces))


def to_trimesh(m: "Mesh | Strips") -> Any:
    """A ``trimesh.Trimesh`` of a :class:`Mesh` (its faces fanned) or of :class:`Strips`
    (the triangles the strips draw, in strip order). Needs trimesh installed."""
    import trimesh  # optional: never a hard dependency

    if isinstance(m, Strips):
        tris = unstripify(m.indices, m._restart).reshape(-1, 3)
        return trimesh.Trimesh(vertices=m.vertices, faces=tris, process=False)
    return trimesh.Trimesh(vertices=m.vertices, faces=m.triangles, process=False)
