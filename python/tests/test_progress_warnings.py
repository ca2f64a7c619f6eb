"""Progress (a callable, counted; a bar, tqdm's or the plain one) and the analysis's
warnings through Python's `warnings`."""

import warnings

import numpy as np
import pytest

import close
from close import _progress
from conftest import FIXTURES, PHYSICS, REFERENCE


def test_a_progress_callable_sees_every_item_done():
    samples = [close.load(p) for p in REFERENCE[:9]]
    calls = []
    results = close.analyze_many(samples, threads=2, progress=lambda done, total: calls.append((done, total)))
    assert len(results) == 9
    assert calls, "the callable was called"
    assert all(total == 9 for _, total in calls)
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[-1] == 9 and len(set(done)) == len(done)


def test_evaluate_reports_progress_over_paths_and_samples():
    calls = []
    close.evaluate(FIXTURES / "physics", progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (len(PHYSICS), len(PHYSICS))
    calls.clear()
    close.evaluate([close.load(p) for p in PHYSICS[:3]], progress=lambda d, t: calls.append((d, t)))
    assert calls[-1] == (3, 3)


def test_evaluate_on_an_executor_reports_progress():
    from concurrent.futures import ThreadPoolExecutor

    calls = []
    with ThreadPoolExecutor(2) as pool:
        report = close.evaluate(FIXTURES / "physics", executor=pool, progress=lambda d, t: calls.append((d, t)))
    assert report == close.evaluate(FIXTURES / "physics")
    assert calls[-1] == (len(PHYSICS), len(PHYSICS)) and [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_a_callable_that_raises_stops_the_batch():
    def stop(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        close.analyze_many([close.load(p) for p in REFERENCE[:4]], progress=stop)


def test_the_plain_bar_draws_on_stderr_without_tqdm(monkeypatch, capsys):
    monkeypatch.setattr(_progress, "_tqdm", lambda: None)
    close.analyze_many([close.load(p) for p in REFERENCE[:3]], progress=True)
    err = capsys.readouterr().err
    assert "close.analyze_many: 3/3 [" in err and "100%" in err and err.endswith("\n")


def test_tqdm_draws_the_bar_when_installed(capsys):
    tqdm = pytest.importorskip("tqdm", reason="tqdm is not installed (.ci/run installs it)")
    assert tqdm
    close.analyze_many([close.load(p) for p in REFERENCE[:3]], progress=True)
    err = capsys.readouterr().err
    assert "close.analyze_many" in err and "3/3" in err


def test_progress_must_be_a_bool_or_a_callable():
    with pytest.raises(TypeError, match="progress"):
        close.analyze_many([close.load(REFERENCE[0])], progress="yes")


def square(n_side=8):
    """An anticlockwise square border of 4·n_side vertices (x, y, 0)."""
    t = np.arange(n_side) / n_side
    sides = [np.c_[t, 0 * t], np.c_[1 + 0 * t, t], np.c_[1 - t, 1 + 0 * t], np.c_[0 * t, 1 - t]]
    return np.c_[np.vstack(sides), np.zeros(4 * n_side)]


def caught(fn):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        result = fn()
    return result, [w for w in seen if issubclass(w.category, close.CloseWarning)]


def test_a_clockwise_border_warns():
    border = square()[::-1]
    analysis, seen = caught(lambda: close.analyze(np.array([border, border])))
    assert analysis.reversed
    assert len(seen) == 1 and "clockwise" in str(seen[0].message) and "input_folds" in str(seen[0].message)
    assert seen[0].filename == __file__  # the caller's line, not the package's
    _, none = caught(lambda: close.analyze(np.array([square(), square()])))
    assert none == []


def test_a_closed_ring_and_merged_duplicates_warn():
    closed = np.vstack([square(), square()[:1]])
    analysis, seen = caught(lambda: close.analyze(np.array([closed, closed])))
    assert [str(w.message) for w in seen] == analysis.warnings and "closed already" in analysis.warnings[0]
    doubled = np.insert(square(), 3, square()[3], axis=0)
    analysis, seen = caught(lambda: close.analyze(np.array([doubled, doubled])))
    assert len(seen) == 1 and "merged 1 duplicate" in str(seen[0].message)
    assert analysis.to_dict()["warnings"] == analysis.warnings


def test_a_batch_warns_once_per_kind_naming_the_items():
    clockwise = np.array([square()[::-1]] * 2)
    plain = np.array([square()] * 2)
    _, seen = caught(lambda: close.analyze_many([clockwise, plain, clockwise, clockwise]))
    assert len(seen) == 1
    assert str(seen[0].message).startswith("items 0, 2, 3: the border was given clockwise")
    assert seen[0].filename == __file__
