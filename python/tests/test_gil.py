"""`analyze_many` releases the GIL: a Python thread keeps counting while it runs."""

import threading
import time

import close
from conftest import REFERENCE


def test_a_python_thread_counts_while_analyze_many_runs():
    samples = [close.load(p) for p in REFERENCE] * 3
    ticks = []
    stop = threading.Event()

    def count():
        n = 0
        while not stop.is_set():
            n += 1
            if n % 1000 == 0:
                ticks.append(time.perf_counter())

    counter = threading.Thread(target=count)
    counter.start()
    try:
        t0 = time.perf_counter()
        results = close.analyze_many(samples, threads=2)
        t1 = time.perf_counter()
    finally:
        stop.set()
        counter.join()
    assert len(results) == len(samples)
    # Held, the GIL would let the counter run at most one switch interval (5 ms) after the
    # call began; released, it counts all through the call. Look at the middle of the call.
    margin = (t1 - t0) / 4
    inside = [t for t in ticks if t0 + margin < t < t1 - margin]
    assert len(inside) >= 10, f"{len(inside)} counter ticks in the middle of a {t1 - t0:.3f} s call"
