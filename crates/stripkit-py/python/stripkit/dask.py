"""A folder of meshes stripped across a Dask cluster.

``strip_folder(src, dst, client=...)`` sends each mesh file of ``src`` to a worker of a
``dask.distributed`` cluster, retries a file whose task fails (a lost worker), writes
each output atomically (a temporary file in ``dst`` renamed over the name) and returns
one row per file: its figures, or the error that stopped it. The outputs are the bytes
``stripkit strip SRC/NAME DST/NAME.ply`` writes.

From a shell, on a running cluster or a local one of ``--workers`` processes::

    python -m stripkit.dask SRC DST [--scheduler tcp://HOST:8786] [--workers 2]

Needs ``pip install stripkit[dask]``.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from typing import Any, Dict, List, Optional

MESH_SUFFIXES = (".obj", ".ply", ".off", ".stl", ".gltf", ".glb", ".obj.gz", ".ply.gz", ".off.gz", ".stl.gz")


def mesh_files(src: "os.PathLike[str] | str") -> List[str]:
    """The mesh files directly in ``src``, sorted by name."""
    names = sorted(n for n in os.listdir(src) if n.lower().endswith(MESH_SUFFIXES))
    return [os.path.join(src, n) for n in names]


def output_name(path: str, format: str = "ply") -> str:
    """``bunny.obj`` -> ``bunny.ply`` (``.gz`` dropped with the extension)."""
    base = os.path.basename(path)
    if base.lower().endswith(".gz"):
        base = base[:-3]
    return os.path.splitext(base)[0] + "." + format


def strip_one(path: str, dst: str, format: str = "ply", options: Optional[Dict[str, Any]] = None) -> Dict[str, Any]:
    """Strips one file into ``dst`` (atomically) and returns its row. Input errors
    (``ValueError``, ``OSError``, ``VerificationError``) become the row's ``error``; any
    other exception propagates, so that Dask retries the task."""
    import stripkit

    row: Dict[str, Any] = {"input": path, "output": None, "error": None}
    start = time.perf_counter()
    try:
        data, figures = stripkit.strip_file(path, format, **(options or {}))
    except (ValueError, OSError, stripkit.VerificationError) as e:
        row["error"] = f"{type(e).__name__}: {e}"
        row["seconds"] = time.perf_counter() - start
        return row
    out = os.path.join(dst, output_name(path, format))
    fd, tmp = tempfile.mkstemp(dir=dst, prefix=".stripkit-", suffix=".part")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, out)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    row.update(output=out, seconds=time.perf_counter() - start, bytes=len(data))
    row.update({k: v for k, v in figures.items() if not isinstance(v, (dict, list))})
    return row


def strip_folder(
    src: "os.PathLike[str] | str",
    dst: "os.PathLike[str] | str",
    *,
    client: Any = None,
    format: str = "ply",
    retries: int = 2,
    **options: Any,
) -> List[Dict[str, Any]]:
    """Strips every mesh file of ``src`` into ``dst`` on the workers of ``client`` (a
    ``dask.distributed.Client``; ``None``: the current default client, else a
    ``LocalCluster`` made and closed here). A task is retried ``retries`` times when it
    fails (a worker lost). Returns one dict per file, in file-name order: ``input``,
    ``output``, ``error`` (``None`` on success), ``seconds``, ``bytes`` and the figures
    (``triangles``, ``strips``, ``acmr``, ...). Keyword ``options`` go to
    :func:`stripkit.stripify_mesh`."""
    from dask.distributed import Client, LocalCluster, default_client

    src, dst = os.fspath(src), os.fspath(dst)
    os.makedirs(dst, exist_ok=True)
    files = mesh_files(src)
    own = None
    if client is None:
        try:
            client = default_client()
        except ValueError:
            own = Client(LocalCluster(processes=True))
            client = own
    try:
        futures = client.map(
            strip_one, files, dst=dst, format=format, options=options, retries=retries, pure=False
        )
        rows = []
        for path, future in zip(files, futures):
            try:
                rows.append(future.result())
            except Exception as e:  # the task failed after its retries
                rows.append({"input": path, "output": None, "error": f"{type(e).__name__}: {e}"})
        return rows
    finally:
        if own is not None:
            cluster = own.cluster
            own.close()
            cluster.close()


def main(argv: Optional[List[str]] = None) -> int:
    """``python -m stripkit.dask SRC DST``: prints one line per file and a total; exit
    status 1 when a file failed."""
    parser = argparse.ArgumentParser(prog="python -m stripkit.dask", description=__doc__.split("\n\n")[0])
    parser.add_argument("src", help="folder of mesh files")
    parser.add_argument("dst", help="folder for the stripped outputs (made if absent)")
    parser.add_argument("--scheduler", help="address of a running scheduler (default: a LocalCluster)")
    parser.add_argument("--workers", type=int, default=None, help="worker processes of the LocalCluster")
    parser.add_argument("--algorithm", default="auto", help="auto, greedy, qstrip, cache, balanced or batch")
    parser.add_argument("--format", default="ply", choices=["ply", "obj"], help="output format")
    parser.add_argument("--retries", type=int, default=2, help="retries of a failed task")
    args = parser.parse_args(argv)
    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True))
    start = time.perf_counter()
    try:
        rows = strip_folder(
            args.src, args.dst, client=client, format=args.format, retries=args.retries, algorithm=args.algorithm
        )
    finally:
        cluster = client.cluster
        client.close()
        if cluster is not None:
            cluster.close()
    failed = 0
    for r in rows:
        if r["error"]:
            failed += 1
            print(f"{r['input']}: {r['error']}", file=sys.stderr)
        else:
            print(f"{r['input']} -> {r['output']}: {r['triangles']} triangles, {r['strips']} strips, acmr {r['acmr']:.3f}")
    print(f"{len(rows) - failed} of {len(rows)} files stripped in {time.perf_counter() - start:.2f} s")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
