"""`.npy` and `.npz` files for `close.load`: read by the native reader as every user file
is, parsed by numpy (no pickles), then the same `Sample` as from arrays."""

import io
import os
from typing import Any, List

import numpy as np

from ._close import CloseError, Sample, _read_file

SUFFIXES = (".npy", ".npz")


def _array(path: str) -> Any:
    # Read as every user file is (a regular file, within the readers' byte cap): missing is
    # FileNotFoundError, a FIFO or a file over the cap CloseError; numpy parses the bytes.
    raw = io.BytesIO(_read_file(path))
    try:
        data = np.load(raw, allow_pickle=False)
    except (ValueError, OSError, EOFError) as e:
        raise CloseError(f"{path}: not a readable numpy file: {e}") from None
    if isinstance(data, np.lib.npyio.NpzFile):
        with data:
            names = list(data.files)
            if "frames" in names:
                return data["frames"]
            if len(names) == 1:
                return data[names[0]]
            raise CloseError(f"{path}: a .npz sample holds a 'frames' array (or one array alone), not {names}")
    return data


def load(paths: List[str]) -> Sample:
    """One ``.npy``/``.npz`` of frames, (F, N, 3) or (F, N, 2) (or one (N, 3)/(N, 2) frame);
    or several ``.npy`` files, one (N, 3) or (N, 2) frame each, in order."""
    if not all(p.lower().endswith(SUFFIXES) for p in paths):
        raise CloseError("give .npy/.npz files alone, not mixed with other formats")
    arrays = [_array(p) for p in paths]
    name = os.path.basename(paths[0])
    if len(arrays) == 1:
        frames = arrays[0]
        if np.ndim(frames) == 2:
            frames = frames[None]
    else:
        bad = [p for p, a in zip(paths, arrays) if np.ndim(a) != 2]
        if bad:
            raise CloseError(f"{bad[0]}: with several .npy files each holds one (N, 3) or (N, 2) frame")
        frames = list(arrays)
    return Sample(frames, name=name, category="upload")
