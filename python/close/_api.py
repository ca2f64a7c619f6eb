"""The package's Python-side functions: argument handling around the native ones (progress
bars, numpy files, spreading `evaluate` over an executor). No maths here."""

import os
from concurrent.futures import Executor, Future, wait, FIRST_COMPLETED
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Union

from . import _close, _numpy_files, _progress
from ._close import Analysis, CloseError, Sample

PathLike = Union[str, "os.PathLike[str]"]

# Parts an executor's work is cut into at most: enough to keep every worker busy, few enough
# that the scheduler's overhead stays small.
_MAX_PARTS = 64


def load(*paths: PathLike) -> Sample:
    """Read a sample from files, as ``close analyze FILE...`` does: one Sample JSON or MATLAB
    .mat file, one text/CSV file per frame, or one OBJ/PLY mesh per frame; and numpy files:
    one ``.npy``/``.npz`` of frames ((F, N, 3), or (F, N, 2) with z = 0; a ``.npz`` holds them
    as ``frames``, or as its one array), or several ``.npy`` files of one frame each.

    The sample is checked as ``Sample(...)`` checks it. A missing file raises
    FileNotFoundError; a file that cannot be parsed, ``close.CloseError``.
    """
    names = [os.fspath(p) for p in paths]
    if any(n.lower().endswith(_numpy_files.SUFFIXES) for n in names):
        return _numpy_files.load(names)
    return _close.load(*names)


def analyze_many(
    items: Iterable[Any],
    *,
    threads: Optional[int] = None,
    method: str = "default",
    progress: Union[bool, None, Callable[[int, int], Any]] = None,
    errors: str = "raise",
) -> List[Union[Analysis, CloseError]]:
    """``close.analyze`` of every item (frames or ``close.Sample``), on ``threads`` native
    threads (default: one per core; at least 1) with the GIL released: other Python threads
    run meanwhile.

    ``progress``: True draws a bar (tqdm's when it is installed, else a plain one on stderr);
    a callable is called as ``progress(done, total)`` from the calling thread as items
    finish. Ctrl-C stops the batch within a fraction of a second (KeyboardInterrupt), its
    threads ended.

    ``errors="raise"`` (default): the first item that fails (the lowest index) raises
    ``close.CloseError`` naming its index, and no item after it is analysed.
    ``errors="return"``: a failed item's place holds its ``close.CloseError``, the others
    are analysed. ``close.to_arrays(results)`` gives the batch as NaN-padded arrays.

    What the analyses repaired or changed (a clockwise border reversed, a closing vertex
    dropped, duplicates merged) is issued as ``close.CloseWarning``s, one per kind, naming
    the items.
    """
    items = list(items)
    callback, close_bar = _progress.bar(progress, len(items), "close.analyze_many")
    try:
        return _close.analyze_many(items, threads=threads, method=method, progress=callback, errors=errors)
    finally:
        close_bar()


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


def _gather(
    executor: Executor,
    parts: List[List[int]],
    submit: Callable[[List[int]], "Future[List[str]]"],
    callback: Optional[Callable[[int, int], Any]],
) -> List[str]:
    """The rows of every part, in order, as the executor's workers finish them; on an
    exception here (Ctrl-C too) the parts not started are cancelled."""
    futures = [submit(part) for part in parts]
    total = sum(len(p) for p in parts)
    sizes = {f: len(p) for f, p in zip(futures, parts)}
    done = 0
    try:
        pending = set(futures)
        while pending:
            finished, pending = wait(pending, return_when=FIRST_COMPLETED)
            for f in finished:
                f.result()  # a worker's exception, here
                done += sizes[f]
            if callback is not None:
                callback(done, total)
    except BaseException:
        for f in futures:
            f.cancel()
        raise
    return [row for f in futures for row in f.result()]


def evaluate(
    items_or_path: Union[PathLike, Sequence[PathLike], Iterable[Any]],
    *,
    threads: Optional[int] = None,
    executor: Optional[Executor] = None,
    method: str = "default",
    progress: Union[bool, None, Callable[[int, int], Any]] = None,
) -> Dict[str, Any]:
    """Evaluate samples as ``close eval --json`` does, and return that object.

    ``items_or_path``: a path (file, folder of Sample JSON files, or a VR-Folding Zarr store
    or one category of it), a list of paths, or a list of samples (``close.Sample`` or frames
    arrays). Per category and overall: count, RMSE and Fréchet mean/var, samples whose fold
    count is not one, and, where ``truth`` is given, the angular error of f1 and f2.

    Units: RMSE, Fréchet and aligned RMSE are in normalised units (the start frame's
    farthest vertex from its centroid is at distance 1); ``f1_error``/``f2_error`` are in
    radians here and in the JSON (the ``close eval`` table prints them in degrees, under
    "f1 err°"); every ``var`` is the population variance (divided by the count, not count − 1).

    For a list of samples each row of ``samples`` keeps the item's place as ``index``, and an
    item without a name (an array) is named ``item <index>``.

    ``threads``: native threads in this process (default: one per core), GIL released.
    ``progress``: True for a bar (tqdm when installed), or a callable ``(done, total)``
    counting samples (or store videos). Ctrl-C stops it (KeyboardInterrupt).
    ``executor``: any ``concurrent.futures.Executor`` (e.g. a Dask
    ``distributed.Client(...).get_executor()``): the work units (sample files, store videos)
    are partitioned over its workers, each worker reads its own units from the path (no
    arrays go through the scheduler), and the rows are gathered, in order, into the same
    report as ``close eval``. The paths must be readable by the workers. A list of samples
    is shipped to the workers instead.
    """
    items: List[Any] = []
    if _is_path(items_or_path):
        paths: Optional[List[str]] = [os.fspath(items_or_path)]  # type: ignore[arg-type]
    else:
        items = list(items_or_path)  # type: ignore[arg-type]
        paths = [os.fspath(p) for p in items] if items and all(_is_path(p) for p in items) else None
    if paths is not None:
        paths = [os.path.abspath(p) for p in paths]
        if executor is None:
            total = _close._eval_units(paths) if progress else 0
            callback, close_bar = _progress.bar(progress, total, "close.evaluate")
            try:
                rows = _close._eval_rows(paths, None, threads=threads, method=method, progress=callback)
            finally:
                close_bar()
        else:
            parts = _parts(_close._eval_units(paths), _MAX_PARTS)
            callback, close_bar = _progress.bar(progress, sum(map(len, parts)), "close.evaluate")
            try:
                rows = _gather(executor, parts, lambda part: executor.submit(_rows_of_paths, paths, part, method), callback)
            finally:
                close_bar()
        return _close._eval_report(rows)
    callback, close_bar = _progress.bar(progress, len(items), "close.evaluate")
    try:
        if executor is None:
            rows = _close._eval_sample_rows(items, threads=threads, method=method, progress=callback)
        else:
            parts = _parts(len(items), _MAX_PARTS)
            rows = _gather(
                executor, parts, lambda part: executor.submit(_rows_of_samples, [items[k] for k in part], method), callback
            )
    finally:
        close_bar()
    report = _close._eval_report(rows)
    for k, row in enumerate(report["samples"]):
        row["index"] = k
        if not row["name"]:
            row["name"] = f"item {k}"
    return report


for _f in (load, analyze_many, evaluate):
    _f.__module__ = "close"
