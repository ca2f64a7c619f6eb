"""What a typed user writes, checked by mypy --strict against the package's stubs
(test_typing.py). Not collected by pytest: it is read by mypy, never run."""

import pickle
from typing import Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

import close


def batch(paths: List[str]) -> Dict[str, object]:
    samples: List[close.Sample] = [close.load(p) for p in paths]
    ok: List[close.Analysis] = close.analyze_many(samples, threads=2, progress=True)
    mixed: List[Union[close.Analysis, close.CloseError]] = close.analyze_many(samples, errors="return")
    arrays = close.to_arrays(mixed)
    first: close.Analysis = ok[0]
    folds: List[Tuple[float, float]] = first.folds
    mine: Optional[List[Tuple[float, float]]] = first.input_folds
    vertices: npt.NDArray[np.int64] = first.corner_vertices
    disk: npt.NDArray[np.float64] = first.disk(-1)
    again: close.Analysis = pickle.loads(pickle.dumps(first))
    same: bool = again == first
    plan: close.PlanDict = close.plan(again, (0.5, 3.6))
    report = close.evaluate(paths, progress=lambda done, total: None)
    warnings: List[str] = first.warnings
    return {"arrays": arrays, "folds": folds, "mine": mine, "vertices": vertices, "disk": disk,
            "same": same, "plan": plan, "report": report, "warnings": warnings}


def inputs(contour: npt.NDArray[np.float64], text: str) -> close.Analysis:
    sample = close.Sample([contour, contour], name="contour")  # (N, 2): z = 0
    close.Sample.from_json(text)
    store = close.vrfolding.open("store.zarr")
    last: close.Sample = store[-1]
    assert last.meta
    return close.analyze(sample, method="paper")
