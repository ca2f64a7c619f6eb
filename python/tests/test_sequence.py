"""A cloth seen only flat and folded: its fold sequence (`steps[k].folds`), and
`close.interpolate` playing it fold by fold (`prior`) to the analysis's predicted end."""

import numpy as np
import pytest

import close
from conftest import PHYSICS

TOWEL = next(p for p in PHYSICS if p.stem.startswith("q5_towel"))


def test_a_sequence_plays_fold_by_fold_to_the_predicted_end():
    towel = close.load(TOWEL)
    ends = close.Sample(towel.frames[[0, -1]], name="towel, flat and folded")
    analysis = close.analyze(ends)
    folds = analysis.to_dict()["steps"][0]["folds"]
    assert len(folds) == 2 and len(analysis.folds) == 2
    flat = ends.frames[0][analysis.border_indices]
    first = close.interpolate(flat, arcs=folds[0]["arcs"], line=folds[0]["line"], steps=2)
    second = close.interpolate(flat, arcs=folds[1]["arcs"], line=folds[1]["line"], steps=5, prior=folds[:1])
    # The second fold starts where the first ended, and ends on the predicted end.
    np.testing.assert_allclose(second[0], first[-1], atol=1e-12)
    np.testing.assert_allclose(second[-1][:, :2], analysis.predicted_end[:, :2], atol=1e-9)


def test_prior_folds_are_checked():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    with pytest.raises(close.CloseError, match="prior fold 1 has no arc"):
        close.interpolate(square, arcs=[(0.0, np.pi)], prior=[{"arcs": [], "line": None}])
    with pytest.raises(close.CloseError, match="prior: each fold a dict"):
        close.interpolate(square, arcs=[(0.0, np.pi)], prior=[{"line": None}])
    with pytest.raises(close.CloseError, match="send no `reference`"):
        close.interpolate(square, arcs=[(0.0, np.pi)], reference=square, prior=[{"arcs": [(0.0, np.pi)]}])


def test_a_goal_of_several_folds_is_planned_in_order():
    # A square, 8 vertices a side, flat: in half (right onto left), then the top half down.
    side = np.linspace(0.0, 1.0, 9)[:-1]
    square = np.concatenate([np.c_[side, 0 * side], np.c_[1 + 0 * side, side], np.c_[1 - side, 1 + 0 * side], np.c_[0 * side, 1 - side]])
    flat = close.analyze(np.stack([square, square]))
    quarters = np.array([[0.25, 1.25], [0.75, 1.75]]) * np.pi
    plan = close.plan(flat, quarters)
    assert plan["case"] == "fold" and len(plan["steps"]) == 2
    assert np.allclose(plan["goal"], quarters)
    # The second fold runs along y = 0.5, on the state the first left.
    line = plan["steps"][1]["line"]
    assert abs(line["direction"][1]) < 1e-9 and abs(line["point"][1] - 0.5) < 1e-9
    # One fold as a pair, and the flat cloth as no fold.
    assert close.plan(flat, (0.25 * np.pi, 1.25 * np.pi))["steps"][0] == plan["steps"][0]
    assert close.plan(flat, [])["case"] == "already_there"
    with pytest.raises(close.CloseError, match=r"goal: expected one fold"):
        close.plan(flat, np.zeros((2, 3)))
