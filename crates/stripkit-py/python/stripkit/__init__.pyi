"""Type stubs of the stripkit package (docstrings in __init__.py)."""

import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._stripkit import DEFAULT_RESTART as DEFAULT_RESTART
from ._stripkit import Lod as Lod
from ._stripkit import Mesh as Mesh
from ._stripkit import VerificationError as VerificationError

_Path = Union[str, "os.PathLike[str]"]
_U32 = npt.NDArray[np.uint32]

def stripify(
    indices: npt.ArrayLike,
    vertex_count: Optional[int] = None,
    *,
    algorithm: str = "auto",
    restart_index: int = ...,
    cache_size: int = 16,
    join: str = "restart",
) -> _U32: ...
def stripify_bound(index_count: int) -> int: ...
def acmr(indices: npt.ArrayLike, vertex_count: Optional[int] = None, *, cache_size: int = 16) -> float: ...
def unstripify(strip: npt.ArrayLike, restart_index: int = ...) -> _U32: ...
def mesh(vertices: npt.ArrayLike, faces: npt.ArrayLike) -> Mesh: ...

class Strips:
    figures: Dict[str, Any]
    @property
    def indices(self) -> _U32: ...
    @property
    def strips(self) -> List[_U32]: ...
    @property
    def vertices(self) -> npt.NDArray[np.float32]: ...
    @property
    def algorithm(self) -> str: ...
    def to_bytes(self, format: str = "ply", *, ascii: bool = False) -> bytes: ...

def stripify_mesh(
    vertices: Union[npt.ArrayLike, Mesh],
    faces: Optional[npt.ArrayLike] = None,
    *,
    algorithm: str = "auto",
    restart_index: int = ...,
    cache_size: int = 16,
    join: str = "restart",
    weld: bool = True,
) -> Strips: ...
def read(path: _Path) -> Mesh: ...
def write(path: _Path, mesh_or_strips: Union[Mesh, Strips], *, ascii: bool = False) -> None: ...
def strip_file(src: _Path, format: str = "ply", **options: Any) -> Tuple[bytes, Dict[str, Any]]: ...
def simplify(
    m: Mesh, ratio: float = 0.5, *, triangles: Optional[int] = None
) -> Tuple[Mesh, _U32, npt.NDArray[np.float64]]: ...
def match(node_count: int, edges: npt.ArrayLike, weights: npt.ArrayLike, *, minimize: bool = False) -> Dict[str, Any]: ...
def from_trimesh(tm: Any) -> Mesh: ...
def to_trimesh(m: Union[Mesh, Strips]) -> Any: ...
def lod_build(m: Mesh, *, algorithm: str = "auto", cache_size: int = 16) -> Lod: ...
def lod_read(path: _Path) -> Lod: ...
def lod_extract(
    lod: Lod,
    *,
    level: Optional[int] = None,
    triangles: Optional[int] = None,
    ratio: Optional[float] = None,
    frame: Optional[float] = None,
) -> Tuple[npt.NDArray[np.float32], List[_U32], int, int]: ...
