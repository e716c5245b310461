from typing import Any, Dict, List, Optional, Union
import os

MESH_SUFFIXES: tuple

def mesh_files(src: Union[str, "os.PathLike[str]"]) -> List[str]: ...
def output_name(path: str, format: str = "ply") -> str: ...
def strip_one(path: str, dst: str, format: str = "ply", options: Optional[Dict[str, Any]] = None) -> Dict[str, Any]: ...
def strip_folder(
    src: Union[str, "os.PathLike[str]"],
    dst: Union[str, "os.PathLike[str]"],
    *,
    client: Any = None,
    format: str = "ply",
    retries: int = 2,
    **options: Any,
) -> List[Dict[str, Any]]: ...
def main(argv: Optional[List[str]] = None) -> int: ...
