"""CloSE: a geometric, shape-agnostic cloth state representation.

Python bindings of the Rust library behind the ``close`` command line and web app: every
number is the CLI's own (the same code), nothing is re-implemented in Python.

Conventions (Kamat, Borràs, Torras, "CloSE"): a border is a closed polyline of N vertices
listed anticlockwise seen from +z (z up, the table is the XY plane); arrays are numpy
float64, (F, N, 3) for frames and (N, 3) for one border. Angles are radians in [0, 2π):
vertex k sits at angle 2πk/N (a fractional vertex index s at 2πs/N). A fold (f1, f2) has
its folded side anticlockwise from f1 to f2. The CloSE value of a state is its corner
angles and one (f1, f2) per fold.

>>> import close
>>> sample = close.load("sample.json")          # doctest: +SKIP
>>> analysis = close.analyze(sample)            # doctest: +SKIP
>>> analysis.folds, analysis.label              # doctest: +SKIP

Bad input raises ``close.CloseError`` (a ``ValueError``) with the CLI's message; a missing
file, ``FileNotFoundError``. The server's input limits hold here too.
"""

import os
from concurrent.futures import Executor
from typing import Any, Dict, Iterable, List, Optional, Sequence, Union

from . import vrfolding
from ._close import (
    Analysis,
    CloseError,
    Sample,
    __version__,
    analyze,
    analyze_many,
    dgli_disk,
    disk_layout,
    distance,
    interpolate,
    load,
    plan,
    verify,
)
from . import _close

__all__ = [
    "Analysis",
    "CloseError",
    "Sample",
    "analyze",
    "analyze_many",
    "dgli_disk",
    "disk_layout",
    "distance",
    "evaluate",
    "interpolate",
    "load",
    "plan",
    "verify",
    "vrfolding",
]

PathLike = Union[str, "os.PathLike[str]"]

# Parts an executor's work is cut into at most: enough to keep every worker busy, few enough
# that the scheduler's overhead stays small.
MAX_PARTS = 64


def _is_path(x: Any) -> bool:
    return isinstance(x, (str, os.PathLike))


def _parts(count: int, parts: int) -> List[List[int]]:
    """``range(count)`` cut into ``parts`` contiguous runs (so the rows keep their order)."""
    parts = max(1, min(count, parts))
    bounds = [count * k // parts for k in range(parts + 1)]
    return [list(range(a, b)) for a, b in zip(bounds, bounds[1:]) if b > a]


def _rows_of_paths(paths: List[str], indices: List[int], method: str) -> List[str]:
    """One worker's share: it reads units ``indices`` of ``paths`` itself and scores them."""
    return _close._eval_rows(paths, indices, method=method)


def _rows_of_samples(items: List[Any], method: str) -> List[str]:
    return _close._eval_sample_rows(items, method=method)


def evaluate(
    items_or_path: Union[PathLike, Sequence[PathLike], Iterable[Any]],
    *,
    threads: Optional[int] = None,
    executor: Optional[Executor] = None,
    method: str = "default",
) -> Dict[str, Any]:
    """Evaluate samples as ``close eval --json`` does, and return that object.

    ``items_or_path``: a path (file, folder of Sample JSON files, or a VR-Folding Zarr store
    or one category of it), a list of paths, or a list of samples (``close.Sample`` or frames
    arrays). Per category and overall: count, RMSE and Fréchet mean/var, samples whose fold
    count is not one, and, where ``truth`` is given, the angular error of f1 and f2 (radians).

    ``threads``: native threads in this process (default: one per core), GIL released.
    ``executor``: any ``concurrent.futures.Executor`` (e.g. a Dask
    ``distributed.Client(...).get_executor()``): the work units (sample files, store videos)
    are partitioned over its workers, each worker reads its own units from the path (no
    arrays go through the scheduler), and the rows are gathered, in order, into the same
    report as ``close eval``. The paths must be readable by the workers. A list of samples
    is shipped to the workers instead.
    """
    if _is_path(items_or_path):
        paths: Optional[List[str]] = [os.fspath(items_or_path)]
    else:
        items = list(items_or_path)
        paths = [os.fspath(p) for p in items] if items and all(_is_path(p) for p in items) else None
    if paths is not None:
        paths = [os.path.abspath(p) for p in paths]
        if executor is None:
            rows = _close._eval_rows(paths, None, threads=threads, method=method)
        else:
            parts = _parts(_close._eval_units(paths), MAX_PARTS)
            futures = [executor.submit(_rows_of_paths, paths, part, method) for part in parts]
            rows = [row for f in futures for row in f.result()]
    elif executor is None:
        rows = _close._eval_sample_rows(items, threads=threads, method=method)
    else:
        parts = _parts(len(items), MAX_PARTS)
        futures = [executor.submit(_rows_of_samples, [items[k] for k in part], method) for part in parts]
        rows = [row for f in futures for row in f.result()]
    return _close._eval_report(rows)
