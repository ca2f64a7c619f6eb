"""`close.verify` and `close.distance`: the CLI's numbers, single pairs and batches."""

import math

import numpy as np
import pytest

import close
from conftest import FIXTURES, cli_json

SQUARE = FIXTURES / "plan" / "square_cw_diagonal.json"
Q3 = FIXTURES / "physics" / "q3_napkin_half_then_quarter_31x31.json"


def test_verify_is_close_verify_json():
    goal = [(0.0, math.pi)]
    answer = close.verify(close.load(SQUARE), goal)
    assert answer == cli_json("verify", SQUARE, "--goal", "0,3.141592653589793")
    assert answer["reached"] and answer["text"].startswith("goal reached")
    # From an Analysis made here, the same answer.
    assert close.verify(close.analyze(close.load(SQUARE)), goal) == answer


def test_verify_a_goal_not_reached_names_the_fold_and_the_grasp():
    answer = close.verify(close.load(SQUARE), np.array([[math.pi / 2, 3 * math.pi / 2]]))
    assert not answer["reached"]
    fold = answer["folds"][0]
    assert fold["status"] == "misplaced"
    assert fold["error_edges"] == pytest.approx([-4.0, -4.0])
    assert fold["error_percent"] == pytest.approx([-25.0, -25.0])
    assert "grasp vertex 12" in answer["text"]
    strict = close.verify(close.load(SQUARE), [(0.0, math.pi)], tolerance_rmse=0.0, tolerance_edges=0.0)
    assert strict["tolerance"] == {"edges": 0.0, "aligned_rmse": 0.0}


def test_verify_takes_a_sequence_and_an_analysis_as_the_goal():
    sample = close.load(Q3)
    analysis = close.analyze(sample)
    own = close.verify(sample, analysis)
    assert own["reached"] and own["distance"]["folds"] == 0.0
    assert own["goal"] == [list(f) for f in analysis.folds]
    # Its CloSE value as a dict, the same.
    assert close.verify(analysis, analysis.close)["folds"] == own["folds"]


def test_verify_refuses_bad_goals_before_any_work():
    with pytest.raises(close.CloseError, match="not finite"):
        close.verify(close.load(SQUARE), [(float("nan"), 1.0)])
    with pytest.raises(close.CloseError, match="not a batch"):
        close.verify(close.load(SQUARE), np.zeros((2, 1, 2)))
    with pytest.raises(close.CloseError, match=r"\(K, 2\)"):
        close.verify(close.load(SQUARE), [1.0, 2.0, 3.0])


def test_distance_of_states_and_of_batches():
    n = 16
    edge = 2 * math.pi / n
    half = (0.0, 8 * edge)
    assert close.distance([half], [half]) == 0.0
    assert close.distance([half], [(edge, 8 * edge)]) == pytest.approx(1 / n)
    assert close.distance([], [half]) == pytest.approx(0.5)
    # A batch: (B, K, 2) with NaN padding, against one goal, and pair by pair.
    rng = np.random.default_rng(7)
    batch = np.full((1000, 2, 2), np.nan)
    batch[:, 0, 0] = rng.uniform(0, 2 * math.pi, 1000)
    batch[:, 0, 1] = (batch[:, 0, 0] + rng.uniform(0.1, 6.0, 1000)) % (2 * math.pi)
    d = close.distance(batch, [half])
    assert d.shape == (1000,)
    for k in range(0, 1000, 97):
        assert d[k] == close.distance([tuple(batch[k, 0])], [half])
    assert np.array_equal(close.distance(batch, batch), np.zeros(1000))
    assert np.array_equal(close.distance(batch, [half]), close.distance([half], batch))


def test_distance_between_analyses_and_geometric():
    a = close.analyze(close.load(SQUARE))
    assert close.distance(a, a) == 0.0
    assert close.distance(a, a, kind="geometric") == pytest.approx(0.0, abs=1e-12)
    border = close.load(SQUARE).frames[0][::-1]  # the file lists it clockwise
    other = [(math.pi / 2, 3 * math.pi / 2)]
    geometric = close.distance(a.close, other, kind="geometric", border=border)
    assert geometric > 0.1
    with pytest.raises(close.CloseError, match="border"):
        close.distance(a.close, other, kind="geometric")
    with pytest.raises(close.CloseError, match="kind"):
        close.distance(a, a, kind="nope")
    with pytest.raises(close.CloseError, match="2 and 3"):
        close.distance(np.zeros((2, 1, 2)) + [0.0, 1.0], np.zeros((3, 1, 2)) + [0.0, 1.0])
