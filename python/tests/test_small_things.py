"""The small things: sequence indexing of a store, a bad thread count, real defaults in
signatures, no helper leaking into the package's namespace, and the benchmark's verdict."""

import inspect
import json
import subprocess
import sys

import numpy as np
import pytest

import close
from conftest import REFERENCE, ROOT, STORE


def test_a_store_indexes_as_a_list():
    store = close.vrfolding.open(STORE)
    actions = list(store)
    assert len(actions) >= 2
    assert store[-1] == actions[-1] and store[-len(store)] == actions[0] and store[0] == actions[0]
    for k in [len(store), -len(store) - 1, 2**62]:
        with pytest.raises(IndexError):
            store[k]


@pytest.mark.parametrize("threads", [0, -1, -(2**40)])
def test_a_bad_thread_count_is_a_value_error(threads):
    sample = close.load(REFERENCE[0])
    for call in (lambda: close.analyze_many([sample], threads=threads), lambda: close.evaluate([sample], threads=threads)):
        with pytest.raises(ValueError, match="threads must be at least 1"):
            call()


def test_signatures_show_real_defaults():
    for fn in [close.Sample, close.analyze, close.analyze_many, close.evaluate, close.load, close.interpolate, close.dgli_disk]:
        text = str(inspect.signature(fn))
        assert "Ellipsis" not in text and "..." not in text, f"{fn.__name__}{text}"
    sample = inspect.signature(close.Sample).parameters
    assert (sample["name"].default, sample["category"].default, sample["truth"].default) == ("", "", None)
    many = inspect.signature(close.analyze_many).parameters
    assert (many["threads"].default, many["progress"].default, many["errors"].default) == (None, None, "raise")


def test_only_the_api_is_public():
    public = {name for name in dir(close) if not name.startswith("_")}
    assert public == set(close.__all__)
    for leaked in ["Any", "Dict", "os", "MAX_PARTS", "Optional", "Executor"]:
        assert not hasattr(close, leaked), leaked


def test_the_benchmark_fails_when_it_misses_a_target():
    """Run with a handful of samples against an impossible threads target: it must say so
    and exit non-zero (with its measured ratios), not 0."""
    done = subprocess.run(
        [sys.executable, str(ROOT / "benches" / "python_targets.py"), "--samples", "8", "--repeats", "1",
         "--disk-n", "60", "--threads-target", "1e9"],
        capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 1, done.stdout + done.stderr
    assert "MISSED" in done.stdout and "threads" in done.stdout
    assert "load average" in done.stdout
