"""`Sample` and `Analysis` pickle (as their JSON, and an analysis with the frames that redo
it), so they travel to executor workers and back; `==` compares values."""

import json
import pickle

import numpy as np
import pytest

import close
from conftest import PHYSICS, STORE, cli_json


def test_a_sample_pickles():
    sample = close.load(PHYSICS[0])
    again = pickle.loads(pickle.dumps(sample))
    assert isinstance(again, close.Sample)
    assert (again.name, again.category, again.truth, again.meta) == (sample.name, sample.category, sample.truth, sample.meta)
    np.testing.assert_array_equal(again.frames, sample.frames)
    assert again.to_json() == sample.to_json()
    assert again == sample and again is not sample


def test_a_sample_made_in_python_pickles_with_its_truth():
    frames = np.array([[[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]] * 2)
    sample = close.Sample(frames, name="square", category="napkin", truth={"folds": [[0.0, 3.14]]})
    again = pickle.loads(pickle.dumps(sample))
    assert again.truth == {"folds": [[0.0, 3.14]]} and again.name == "square"
    np.testing.assert_array_equal(again.frames, frames)


def test_a_store_action_pickles_with_its_meta():
    action = next(iter(close.vrfolding.open(STORE)))
    again = pickle.loads(pickle.dumps(action))
    assert again.meta == action.meta and set(again.meta) == {"video_id", "category", "fold"}
    np.testing.assert_array_equal(again.frames, action.frames)
    assert again == action


def test_samples_compare_by_value():
    a, b = close.load(PHYSICS[0]), close.load(PHYSICS[0])
    assert a == b and not (a != b)
    assert a != close.load(PHYSICS[1])
    assert close.Sample(a.frames, name="other") != close.Sample(a.frames)
    assert a != "not a sample"


def test_an_analysis_pickles():
    analysis = close.analyze(close.load(PHYSICS[0]))
    again = pickle.loads(pickle.dumps(analysis))
    assert isinstance(again, close.Analysis)
    assert again.to_dict() == analysis.to_dict()
    assert again.folds == analysis.folds and again.corners == analysis.corners and again.label == analysis.label
    np.testing.assert_array_equal(again.predicted_end, analysis.predicted_end)
    np.testing.assert_array_equal(again.border_indices, analysis.border_indices)


def test_analyses_compare_by_value():
    sample = close.load(PHYSICS[0])
    a, b = close.analyze(sample), close.analyze(sample)
    assert a is not b and a == b
    assert pickle.loads(pickle.dumps(a)) == a
    assert a != close.analyze(sample, method="paper") or a.to_dict() == close.analyze(sample, method="paper").to_dict()
    assert a != close.analyze(close.load(PHYSICS[1]))
    assert a != a.to_dict()


@pytest.mark.parametrize("path", [p for p in PHYSICS if "then" in p.stem][:1] + PHYSICS[:1], ids=lambda p: p.stem)
def test_an_unpickled_analysis_plans_as_the_original(path):
    sample = close.load(path)
    goal = (0.5, 3.6)
    for kwargs in [{}, {"start": 1}, {"method": "paper"}]:
        if kwargs.get("start", 0) >= len(sample.frames) - 1:
            continue
        analysis = close.analyze(sample, **kwargs)
        again = pickle.loads(pickle.dumps(analysis))
        assert close.plan(again, goal) == close.plan(analysis, goal)
        np.testing.assert_array_equal(again.disk(-1), analysis.disk(-1))
    # And as the CLI plans from the file.
    expected = cli_json("plan", path, "--goal", "0.5,3.6")
    answer = close.plan(pickle.loads(pickle.dumps(close.analyze(sample))), goal)
    assert answer == expected


def test_an_analysis_that_cannot_be_redone_says_so():
    analysis = close.analyze(close.load(PHYSICS[0]))
    rebuild, (text, redo) = analysis.__reduce__()
    # Without its frames (an older pickle): no plan, a clear error.
    with pytest.raises(close.CloseError, match="without its frames"):
        close.plan(rebuild(text), (0.5, 3.6))
    # With frames that do not give the analysis it claims (another version's): refused.
    value = json.loads(text)
    value["folds"] = [[0.1, 0.2]]
    with pytest.raises(close.CloseError, match="could not be redone"):
        close.plan(rebuild(json.dumps(value), redo), (0.5, 3.6))
    with pytest.raises(close.CloseError, match="analysis state"):
        rebuild(text, (redo[0][:-8], redo[1], redo[2]))
