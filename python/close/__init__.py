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
file, ``FileNotFoundError``. The server's input limits hold here too. What an analysis
repaired in its input (a clockwise border reversed, a closing vertex dropped, duplicates
merged) is a ``close.CloseWarning`` (Python's ``warnings``).

(N, 2) borders and (F, N, 2) frames, as 2-D contour extraction gives them, are x, y on the
table (z = 0). Metrics (RMSE, Fréchet, aligned RMSE) are in normalised units: the start
frame's farthest vertex from its centroid is at distance 1. Corners are numbered from 1 in
the label and the plan ("corner 1" is ``Analysis.corners[0]``, at border vertex
``Analysis.corner_vertices[0]``); their structured fields carry each corner's vertex index
beside its number. ``python -m close analyze|eval|plan`` runs the command line's commands.
"""

from . import vrfolding
from ._api import analyze_many, evaluate, load
from ._close import (
    Analysis,
    CloseError,
    CloseWarning,
    Sample,
    __version__,
    analyze,
    dgli_disk,
    disk_layout,
    distance,
    interpolate,
    plan,
    to_arrays,
    verify,
)

__all__ = [
    "Analysis",
    "CloseError",
    "CloseWarning",
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
    "to_arrays",
    "verify",
    "vrfolding",
]
