"""Batch results for arrays and pandas: `errors="return"`, `evaluate` rows that keep each
item's index and name, and `close.to_arrays` (NaN-padded)."""

import numpy as np
import pytest

import close
from conftest import PHYSICS, REFERENCE

SQUARE = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
BAD = np.array([SQUARE, SQUARE * np.nan])  # frame 1 is NaN


def test_errors_return_puts_the_error_in_the_items_place():
    good = [close.load(p) for p in REFERENCE[:3]]
    items = [good[0], BAD, good[1], "not an array", good[2]]
    results = close.analyze_many(items, threads=2, errors="return")
    assert len(results) == 5
    assert [type(r).__name__ for r in results] == ["Analysis", "CloseError", "Analysis", "CloseError", "Analysis"]
    assert "item 1: non-finite coordinate in frame 1" in str(results[1])
    assert str(results[3]).startswith("item 3: ")
    assert [r.to_dict() for r in results[::2]] == [close.analyze(s).to_dict() for s in good]


def test_errors_raise_names_the_first_failing_item():
    good = close.load(REFERENCE[0])
    with pytest.raises(close.CloseError, match="^item 2: "):
        close.analyze_many([good, good, BAD, good, BAD], threads=2)
    with pytest.raises(close.CloseError, match="^item 1: "):
        close.analyze_many([good, "not an array", BAD])
    with pytest.raises(close.CloseError, match='errors must be "raise" or "return"'):
        close.analyze_many([good], errors="ignore")


def test_evaluate_rows_keep_index_and_name():
    sample = close.load(PHYSICS[0])
    report = close.evaluate([sample, sample.frames, BAD])
    rows = report["samples"]
    assert [r["index"] for r in rows] == [0, 1, 2]
    assert [r["name"] for r in rows] == [sample.name, "item 1", "item 2"]
    assert rows[2]["error"] and not rows[0]["error"]
    assert rows[0]["rmse"] == rows[1]["rmse"]


def test_to_arrays_pads_with_nan():
    paths = [p for p in PHYSICS if "then" in p.stem][:1] + REFERENCE[:3]
    samples = [close.load(p) for p in paths]
    results = close.analyze_many(samples + [BAD], errors="return")
    arrays = close.to_arrays(results)
    b = len(results)
    most_corners = max(len(r.corners) for r in results[:-1])
    most_folds = max(len(r.folds) for r in results[:-1])
    assert most_folds >= 2, "a two-fold sample pads the others"
    assert arrays["corners"].shape == (b, most_corners) and arrays["folds"].shape == (b, most_folds, 2)
    for k, r in enumerate(results[:-1]):
        c, f = len(r.corners), len(r.folds)
        np.testing.assert_array_equal(arrays["corners"][k, :c], r.corners)
        assert np.isnan(arrays["corners"][k, c:]).all()
        np.testing.assert_array_equal(arrays["folds"][k, :f], np.array(r.folds).reshape(f, 2))
        assert np.isnan(arrays["folds"][k, f:]).all()
        assert (arrays["n"][k], arrays["corner_count"][k], arrays["fold_count"][k]) == (r.n, c, f)
        for key in ("rmse", "frechet", "aligned_rmse"):
            assert arrays[key][k] == r.metrics[key]
        assert arrays["error"][k] is None
    # The failed item: a row of NaN and its message.
    assert np.isnan(arrays["corners"][-1]).all() and np.isnan(arrays["rmse"][-1]) and arrays["n"][-1] == 0
    assert "non-finite" in arrays["error"][-1]
    # The one-dimensional entries are columns of one length (a DataFrame's).
    columns = {k: v for k, v in arrays.items() if np.ndim(v) == 1}
    assert set(columns) == {"n", "corner_count", "fold_count", "rmse", "frechet", "aligned_rmse", "error"}
    assert {len(v) for v in columns.values()} == {b}
    assert arrays["corners"].dtype == arrays["folds"].dtype == np.float64 and arrays["n"].dtype == np.int64


def test_to_arrays_of_nothing_and_of_the_wrong_things():
    empty = close.to_arrays([])
    assert empty["corners"].shape == (0, 0) and empty["folds"].shape == (0, 0, 2) and empty["error"] == []
    with pytest.raises(TypeError, match="item 0: expected a close.Analysis"):
        close.to_arrays(["nope"])
