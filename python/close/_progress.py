"""Progress bars of `analyze_many` and `evaluate`: tqdm's when it is installed, else a plain
one on stderr; or the caller's own callable."""

import sys
import time
from typing import Any, Callable, Optional, Tuple

Callback = Callable[[int, int], Any]


class _PlainBar:
    """``close: 120/1000 [###.................] 12%  3.1 s`` on stderr, redrawn in place."""

    WIDTH = 30

    def __init__(self, total: int, desc: str) -> None:
        self.total, self.desc, self.start, self.drawn = total, desc, time.monotonic(), False

    def __call__(self, done: int, total: int) -> None:
        filled = self.WIDTH * done // max(total, 1)
        percent = 100 * done // max(total, 1)
        elapsed = time.monotonic() - self.start
        bar = "#" * filled + "." * (self.WIDTH - filled)
        sys.stderr.write(f"\r{self.desc}: {done}/{total} [{bar}] {percent:3d}% {elapsed:6.1f} s")
        sys.stderr.flush()
        self.drawn = True

    def close(self) -> None:
        if self.drawn:
            sys.stderr.write("\n")
            sys.stderr.flush()


class _TqdmBar:
    def __init__(self, tqdm: Any, total: int, desc: str) -> None:
        self.bar = tqdm(total=total, desc=desc, unit="item")

    def __call__(self, done: int, total: int) -> None:
        self.bar.update(done - self.bar.n)

    def close(self) -> None:
        self.bar.close()


def _tqdm() -> Optional[Any]:
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm


def bar(progress: Any, total: int, desc: str) -> Tuple[Optional[Callback], Callable[[], None]]:
    """The callback for ``progress`` (True: a bar; a callable: itself; None/False: none) and
    what closes it when the work ends."""
    if progress is None or progress is False:
        return None, lambda: None
    if progress is True:
        tqdm = _tqdm()
        drawn = _TqdmBar(tqdm, total, desc) if tqdm is not None else _PlainBar(total, desc)
        return drawn, drawn.close
    if callable(progress):
        return progress, lambda: None
    raise TypeError(f"progress must be True, False, None or a callable (done, total), not {type(progress).__name__}")
