"""Type stubs of the `close` package (CloSE cloth-state representation).

Angles are radians in [0, 2π), vertex k of N at 2πk/N; a fold (f1, f2) has its folded side
anticlockwise from f1 to f2. Arrays are numpy float64.

The dicts the package returns are the JSON answers of the `close` command line and server,
typed below: each `TypedDict` names the schema it follows (`schema/*.json` of the repository,
generated from the Rust types), and `tests/it/schema.rs` checks their keys against it.
"""

import os
from concurrent.futures import Executor
from typing import Any, Callable, Dict, Iterable, List, Literal, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt
from typing_extensions import NotRequired, TypedDict

from . import vrfolding as vrfolding

__version__: str

PathLike = Union[str, os.PathLike[str]]
Frames = Union[npt.ArrayLike, Sequence[npt.ArrayLike]]
FloatArray = npt.NDArray[np.float64]

# The analysis (`Analysis.to_dict()`, `close analyze --json`): schema/analysis.json.

Pair = List[float]
Point3 = List[float]

class LineDict(TypedDict):
    """A fold line in XY (schema/analysis.json#/$defs/Line)."""

    point: Pair
    direction: Pair

class MetricsDict(TypedDict):
    """Errors of a predicted border (schema/analysis.json#/$defs/Metrics)."""

    rmse: float
    frechet: float
    aligned_rmse: float

class CloseDict(TypedDict):
    """The CloSE value (schema/analysis.json#/$defs/Close)."""

    corners: List[float]
    folds: List[Pair]

class SideFoldDict(TypedDict):
    """schema/analysis.json#/$defs/SideFold"""

    from_corner: int
    to_corner: int
    from_vertex: int
    to_vertex: int
    folded_percent: float

class FoldedCornerDict(TypedDict):
    """schema/analysis.json#/$defs/FoldedCorner"""

    corner: int
    vertex: int
    before: SideFoldDict
    after: SideFoldDict

FoldClass = Literal[
    "folded_in_half",
    "diagonally_folded_in_half",
    "one_side_folded",
    "folded_in_half_askew",
    "one_side_askew",
    "corner_folded",
    "folded",
]

# The label of one fold ("class" is a Python keyword: the call form).
# schema/analysis.json#/$defs/FoldLabel
FoldLabelDict = TypedDict(
    "FoldLabelDict",
    {
        "class": FoldClass,
        "folded_corners": List[int],
        "folded_corner_vertices": List[int],
        "corners_on_fold_line": List[int],
        "corner_vertices_on_fold_line": List[int],
        "corner_sides": List[FoldedCornerDict],
        "cut_sides": List[SideFoldDict],
        "folded_percent": float,
        "border_degrees": Pair,
        "text": str,
    },
)

SequenceClass = Literal[
    "in_quarters", "in_eighths", "in_thirds", "sides_in_then_half", "half_then_sides_in", "folds"
]

# How a sequence of folds reads as a whole. schema/analysis.json#/$defs/SequenceLabel
SequenceLabelDict = TypedDict(
    "SequenceLabelDict",
    {
        "class": SequenceClass,
        "across_percent": List[Optional[float]],
        "in_half": List[bool],
        "text": str,
    },
)

class LabelDict(TypedDict):
    """The semantic label (schema/analysis.json#/$defs/Label)."""

    text: str
    corners: int
    circular: bool
    folds: List[FoldLabelDict]
    sequence: Optional[SequenceLabelDict]

class CurveDict(TypedDict):
    """A fold curve θ = a0 + a1·r on the diff disk (schema/analysis.json#/$defs/Curve)."""

    a0: float
    a1: float
    loss: float
    rim: float

class CutDict(TypedDict):
    """schema/analysis.json#/$defs/Cut"""

    p1: float
    p2: float
    residual: float
    same_to_cross: float
    inside_edge: List[bool]

class OrientationDict(TypedDict):
    """schema/analysis.json#/$defs/Orientation"""

    flip_forward: float
    flip_backward: float
    tie_break: bool
    swapped: bool

class SynthesisDict(TypedDict):
    """The refinement by synthesis, in border parameters (schema/analysis.json#/$defs/Synthesis)."""

    s: Pair
    arcs: List[Pair]
    direction: Optional[Pair]
    mismatch: float
    unfolded_mismatch: float

class ExplainedFoldDict(TypedDict):
    """One fold of a step's sequence (schema/analysis.json#/$defs/ExplainedFold)."""

    fold: Pair
    arcs: List[Pair]
    line: Optional[LineDict]
    explained: Optional[float]

class AlternativeDict(TypedDict):
    """Another sequence that reads the step almost as well (schema/analysis.json#/$defs/Alternative)."""

    folds: List[ExplainedFoldDict]
    explained: float

Reason = Literal[
    "same_to_cross",
    "residual",
    "changed_without_fold",
    "unexplained",
    "tie_break",
    "flip_margin",
    "prediction",
]

class DoubtDict(TypedDict):
    """schema/analysis.json#/$defs/Doubt"""

    reason: Reason
    value: float
    limit: float
    text: str

class ConfidenceDict(TypedDict):
    """How sure a step's fold is (schema/analysis.json#/$defs/Confidence)."""

    level: Literal["high", "low"]
    doubts: List[DoubtDict]

class StepDict(TypedDict):
    """`steps[k]`: frame k−1 → k (schema/analysis.json#/$defs/Step)."""

    from_frame: int
    to_frame: int
    fold: Optional[Pair]
    arcs: List[Pair]
    curves: List[CurveDict]
    cut: Optional[CutDict]
    orientation: Optional[OrientationDict]
    synthesis: Optional[SynthesisDict]
    folds: List[ExplainedFoldDict]
    alternatives: List[AlternativeDict]
    explained: float
    unexplained: bool
    line: Optional[LineDict]
    metrics: MetricsDict
    predicted: List[Point3]
    confidence: ConfidenceDict

class AnalysisDict(TypedDict):
    """What `close analyze --json` prints (schema/analysis.json)."""

    n: int
    corners: List[float]
    corner_vertices: List[int]
    corner_threshold: float
    folds: List[Pair]
    close: CloseDict
    label: LabelDict
    border_indices: List[int]
    border_source: str
    reversed: bool
    warnings: List[str]
    start_frame: int
    end_frame: int
    steps: List[StepDict]
    predicted_end: List[Point3]
    metrics: Optional[MetricsDict]

# The plan (`close.plan`, `POST /api/plan`, `close plan --json`): schema/plan.json.

# schema/plan.json#/$defs/Pick
PickDict = TypedDict("PickDict", {"vertex": int, "angle": float, "from": Point3, "to": Point3})

class PlanStepDict(TypedDict):
    """schema/plan.json#/$defs/PlanStep"""

    action: Literal["fold", "unfold"]
    fold: Pair
    corners: List[int]
    corner_vertices: List[int]
    picks: List[PickDict]
    line: Optional[LineDict]

class PlanDict(TypedDict):
    """How to reach the goal folds (schema/plan.json)."""

    case: Literal["fold", "direct", "unfold_then_fold", "already_there"]
    steps: List[PlanStepDict]
    goal: List[Pair]
    folds: List[Pair]
    lines: List[Optional[LineDict]]
    corners: List[float]
    start_border: List[Point3]
    border_indices: List[int]

# The evaluation (`close.evaluate`, `close eval --json`): schema/evaluation.json.

class StatDict(TypedDict):
    """Mean and population variance (schema/evaluation.json#/$defs/Stat)."""

    mean: float
    var: float

class FoldSummaryDict(TypedDict):
    """schema/evaluation.json#/$defs/FoldSummary"""

    fold: int
    count: int
    found: int
    rmse: Optional[StatDict]
    frechet: Optional[StatDict]
    aligned_rmse: Optional[StatDict]
    f1_error: Optional[StatDict]
    f2_error: Optional[StatDict]

class SummaryDict(TypedDict):
    """One row of the table (schema/evaluation.json#/$defs/Summary)."""

    category: str
    count: int
    rmse: Optional[StatDict]
    frechet: Optional[StatDict]
    aligned_rmse: Optional[StatDict]
    fold_count_misses: int
    errors: int
    dropped: int
    f1_error: Optional[StatDict]
    f2_error: Optional[StatDict]
    by_fold: NotRequired[List[FoldSummaryDict]]

class StepResultDict(TypedDict):
    """schema/evaluation.json#/$defs/StepResult"""

    fold_found: bool
    rmse: float
    frechet: float
    aligned_rmse: Optional[float]
    angle_error: Optional[Pair]

class SampleResultDict(TypedDict):
    """schema/evaluation.json#/$defs/SampleResult"""

    name: str
    category: str
    folds: int
    expected_folds: int
    rmse: Optional[float]
    frechet: Optional[float]
    aligned_rmse: Optional[float]
    angle_error: Optional[Pair]
    error: Optional[str]
    dropped: NotRequired[str]
    steps: List[StepResultDict]

class UnitsDict(TypedDict):
    """A report's units (schema/evaluation.json#/$defs/Units): angles "rad", lengths
    "normalised" (the start border's)."""

    angle: Literal["rad"]
    length: Literal["normalised"]

class EvaluationDict(TypedDict):
    """What `close eval --json` prints (schema/evaluation.json)."""

    units: UnitsDict
    categories: List[SummaryDict]
    overall: SummaryDict
    samples: List[SampleResultDict]

# A sample's parts (`Sample.truth`, `Sample.mesh`, `Sample.meta`).

class TruthDict(TypedDict):
    """The known folds (schema/sample.json#/$defs/Truth)."""

    folds: List[Pair]
    folded_vertices: NotRequired[List[int]]
    folded_vertices_per_fold: NotRequired[List[List[int]]]

class MeshDict(TypedDict):
    """A mesh sample's mesh: faces and (F, V, 3) vertex frames."""

    faces: List[List[int]]
    frames: FloatArray

class MetaDict(TypedDict, total=False):
    """Where a sample came from: a VR-Folding action's video, category and fold."""

    video_id: str
    category: str
    fold: int

Progress = Union[bool, None, Callable[[int, int], Any]]

class CloseError(ValueError):
    """Bad input, with the message the `close` command line prints."""

class CloseWarning(UserWarning):
    """What an analysis repaired or changed in its input (a clockwise border reversed, a
    closing vertex dropped, duplicate vertices merged)."""

class Sample:
    """A cloth sample: border frames (or a mesh), frame 0 the flat start."""

    def __init__(self, frames: Frames, *, name: str = "", category: str = "", truth: Optional[TruthDict] = None) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def category(self) -> str: ...
    @property
    def frames(self) -> FloatArray:
        """(F, N, 3) vertex positions per frame (a mesh sample: its vertex frames)."""
    @property
    def truth(self) -> Optional[TruthDict]: ...
    @property
    def mesh(self) -> Optional[MeshDict]: ...
    @property
    def meta(self) -> MetaDict: ...
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
    def close(self) -> CloseDict: ...
    @property
    def label(self) -> str: ...
    @property
    def predicted_end(self) -> FloatArray: ...
    @property
    def metrics(self) -> Optional[MetricsDict]: ...
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
    def to_dict(self) -> AnalysisDict:
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
    prior: Optional[Sequence[Mapping[str, Any]]] = None,
) -> FloatArray:
    """(steps, N, 3) borders of the folding motion from fold `from_` to fold `to`, or of a
    fold's `arcs` turned over about `line` (an analysis step's `arcs` and `line`); `prior`:
    folds made first on the flat `border` (an analysis step's `folds` entries), in order."""

def plan(
    sample_or_analysis: Union[Sample, Analysis, Frames],
    goal: Union[Tuple[float, float], Sequence[Tuple[float, float]], npt.ArrayLike],
) -> PlanDict:
    """The `POST /api/plan` answer: how to reach the goal from the sample's state. `goal`: one
    fold (g1, g2) in radians, or folds made in order as a (K, 2) array-like."""

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
) -> EvaluationDict:
    """The object `close eval --json` prints; `executor`: any concurrent.futures.Executor."""
