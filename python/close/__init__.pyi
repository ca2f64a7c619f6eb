"""Type stubs of the `close` package (CloSE cloth-state representation).

Angles are radians in [0, 2π), vertex k of N at 2πk/N; a fold (f1, f2) has its folded side
anticlockwise from f1 to f2. Arrays are numpy float64.
"""

import os
from concurrent.futures import Executor
from typing import Any, Callable, Dict, Iterable, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import vrfolding as vrfolding

__version__: str

PathLike = Union[str, os.PathLike[str]]
Frames = Union[npt.ArrayLike, Sequence[npt.ArrayLike]]
FloatArray = npt.NDArray[np.float64]

Progress = Union[bool, None, Callable[[int, int], Any]]

class CloseError(ValueError):
    """Bad input, with the message the `close` command line prints."""

class CloseWarning(UserWarning):
    """What an analysis repaired or changed in its input (a clockwise border reversed, a
    closing vertex dropped, duplicate vertices merged)."""

class Sample:
    """A cloth sample: border frames (or a mesh), frame 0 the flat start."""

    def __init__(self, frames: Frames, *, name: str = "", category: str = "", truth: Optional[Dict[str, Any]] = None) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def category(self) -> str: ...
    @property
    def frames(self) -> FloatArray:
        """(F, N, 3) vertex positions per frame (a mesh sample: its vertex frames)."""
    @property
    def truth(self) -> Optional[Dict[str, Any]]: ...
    @property
    def mesh(self) -> Optional[Dict[str, Any]]: ...
    @property
    def meta(self) -> Dict[str, Any]: ...
    def to_json(self) -> str: ...
    @classmethod
    def from_json(cls, text: Union[str, bytes]) -> "Sample":
        """A sample from Sample JSON text, checked as `Sample(...)` checks its frames."""

class Analysis:
    """What `close analyze --json` reports about a sample."""

    @property
    def n(self) -> int: ...
    @property
    def corners(self) -> List[float]: ...
    @property
    def folds(self) -> List[Tuple[float, float]]: ...
    @property
    def close(self) -> Dict[str, Any]: ...
    @property
    def label(self) -> str: ...
    @property
    def predicted_end(self) -> FloatArray: ...
    @property
    def metrics(self) -> Optional[Dict[str, float]]: ...
    @property
    def border_indices(self) -> npt.NDArray[np.int64]: ...
    @property
    def corner_vertices(self) -> npt.NDArray[np.int64]:
        """Border vertex of each corner: "corner k" (1-based) is `corners[k - 1]` at `corner_vertices[k - 1]`."""
    @property
    def warnings(self) -> List[str]: ...
    @property
    def reversed(self) -> bool: ...
    @property
    def input_folds(self) -> Optional[List[Tuple[float, float]]]:
        """The folds in the input's own vertex order (None for a mesh sample)."""
    def disk(self, k: int = 0) -> FloatArray:
        """The dGLI disk of analysed frame k (0 the start, -1 the end), as `--disks`."""
    def to_dict(self) -> Dict[str, Any]:
        """The object `close analyze --json` prints, key for key."""
    def to_json(self) -> str: ...

def analyze(frames: Union[Frames, Sample], *, method: str = "default", start: Optional[int] = None, end: Optional[int] = None, max_folds: int = 3) -> Analysis:
    """Analyse frames start → end as `close analyze --json` does (radians, vertex k at 2πk/N,
    folded side anticlockwise from f1 to f2); a step holds up to `max_folds` folds (1 to 4)."""

@overload
def analyze_many(
    items: Iterable[Union[Frames, Sample]],
    *,
    threads: Optional[int] = None,
    method: str = "default",
    progress: Progress = None,
    errors: Literal["raise"] = "raise",
) -> List[Analysis]:
    """`analyze` of every item on native threads, the GIL released; Ctrl-C stops it."""
@overload
def analyze_many(
    items: Iterable[Union[Frames, Sample]],
    *,
    threads: Optional[int] = None,
    method: str = "default",
    progress: Progress = None,
    errors: Literal["return"],
) -> List[Union[Analysis, CloseError]]:
    """`analyze` of every item; a failed item's place holds its `CloseError`."""
def to_arrays(results: Iterable[Union[Analysis, BaseException]]) -> Dict[str, Any]:
    """A batch's results as NaN-padded numpy arrays (`corners` (B, C), `folds` (B, F, 2),
    `rmse`, `frechet`, `aligned_rmse`, `n`, `corner_count`, `fold_count` (B,)) and `error`."""

def load(*paths: PathLike) -> Sample:
    """Read a sample from files (Sample JSON, .mat, text/CSV per frame, OBJ/PLY per frame, .npy/.npz)."""

def dgli_disk(border: npt.ArrayLike, *, reference: Optional[npt.ArrayLike] = None) -> FloatArray:
    """The condensed dGLI pair vector of one (N, 3) border state, as `close analyze --disks`."""

def disk_layout(n: int) -> Tuple[FloatArray, FloatArray]:
    """(radius, angle) of each pair of `dgli_disk`'s vector on the disk."""

def interpolate(
    border: npt.ArrayLike,
    from_: Optional[Tuple[float, float]] = None,
    to: Optional[Tuple[float, float]] = None,
    steps: int = 60,
    *,
    reference: Optional[npt.ArrayLike] = None,
    arcs: Optional[Sequence[Tuple[float, float]]] = None,
    line: Optional[Dict[str, Tuple[float, float]]] = None,
) -> FloatArray:
    """(steps, N, 3) borders of the folding motion from fold `from_` to fold `to`, or of a
    fold's `arcs` turned over about `line` (an analysis step's `arcs` and `line`)."""

def plan(sample_or_analysis: Union[Sample, Analysis, Frames], goal: Tuple[float, float]) -> Dict[str, Any]:
    """The `POST /api/plan` answer: how to reach the goal fold from the sample's state."""

FoldsLike = Union[Analysis, Dict[str, Any], Sequence[Tuple[float, float]], npt.ArrayLike]

def distance(
    a: FoldsLike,
    b: FoldsLike,
    *,
    kind: str = "folds",
    border: Optional[npt.ArrayLike] = None,
) -> Union[float, FloatArray]:
    """Distance between two states of one cloth. `kind="folds"` (default): the fold distance in
    shares of the border (one fold point moved by one edge costs 1/N, a missing or extra fold
    the share it folds over). `kind="geometric"`: the aligned XY RMSE of the two predicted
    borders (normalised units; needs the flat `border`, or two Analyses). `a`, `b`: Analyses,
    CloSE dicts, (K, 2) arrays of folds, or (B, K, 2) batches (NaN rows pad shorter
    sequences; one sequence pairs with every one of a batch): a float, or a (B,) array."""

def verify(
    observed: Union[Sample, Analysis, Frames],
    goal: FoldsLike,
    *,
    tolerance_edges: float = 1.5,
    tolerance_rmse: float = 0.03,
) -> Dict[str, Any]:
    """The `POST /api/verify` answer: `reached`, `text`, `distance` {`folds`, `geometric`},
    `folds` (per goal fold: `status` found/misplaced/missing, `error_edges`, `error_percent`,
    `short_edges`, `other_side`), `extra`, `plan` (a goal of one fold), `tolerance`."""

def evaluate(
    items_or_path: Union[PathLike, Sequence[PathLike], Iterable[Union[Frames, Sample]]],
    *,
    threads: Optional[int] = None,
    executor: Optional[Executor] = None,
    method: str = "default",
    progress: Progress = None,
) -> Dict[str, Any]:
    """The object `close eval --json` prints; `executor`: any concurrent.futures.Executor."""
