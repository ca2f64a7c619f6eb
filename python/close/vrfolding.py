"""VR-Folding Zarr stores (the CloSE paper's Table I data), read by the Rust library.

``close.vrfolding.open(path)`` opens a store (or one category folder of it) and cuts every
video into fold actions, as ``close eval STORE`` does: ``len(store)`` usable actions,
iteration over them as ``close.Sample`` objects (``sample.meta``: ``video_id``,
``category``, ``fold``), ``store.dropped`` folds left out because a mesh they use is broken
(BiFold's z-score test).
"""

from ._close import Store, vrfolding_open as open

__all__ = ["Store", "open"]
