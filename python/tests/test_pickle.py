"""`Sample` and `Analysis` pickle (as their JSON), so they travel to executor workers."""

import pickle

import numpy as np

import close
from conftest import PHYSICS, STORE


def test_a_sample_pickles():
    sample = close.load(PHYSICS[0])
    again = pickle.loads(pickle.dumps(sample))
    assert isinstance(again, close.Sample)
    assert (again.name, again.category, again.truth, again.meta) == (sample.name, sample.category, sample.truth, sample.meta)
    np.testing.assert_array_equal(again.frames, sample.frames)
    assert again.to_json() == sample.to_json()


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


def test_an_analysis_pickles():
    analysis = close.analyze(close.load(PHYSICS[0]))
    again = pickle.loads(pickle.dumps(analysis))
    assert isinstance(again, close.Analysis)
    assert again.to_dict() == analysis.to_dict()
    assert again.folds == analysis.folds and again.corners == analysis.corners and again.label == analysis.label
    np.testing.assert_array_equal(again.predicted_end, analysis.predicted_end)
    np.testing.assert_array_equal(again.border_indices, analysis.border_indices)
