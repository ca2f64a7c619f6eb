"""The numbers are the CLI's own: `close.analyze` against `close analyze --json`, on the
reference and physics fixtures; `dgli_disk` against `--disks`; `evaluate` against `close eval`."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import close
from conftest import PHYSICS, REFERENCE, FIXTURES, cli_json

TOL = 1e-12
SAMPLES = REFERENCE + PHYSICS


def test_fixtures_are_there():
    assert len(REFERENCE) >= 90 and len(PHYSICS) >= 10


@pytest.mark.parametrize("path", SAMPLES, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_analyze_equals_the_cli(path):
    expected = cli_json("analyze", path)
    analysis = close.analyze(close.load(path))
    # Key for key, number for number.
    assert analysis.to_dict() == expected
    assert analysis.n == expected["n"]
    np.testing.assert_allclose(analysis.corners, expected["corners"], rtol=0, atol=TOL)
    assert len(analysis.folds) == len(expected["folds"])
    for got, want in zip(analysis.folds, expected["folds"]):
        np.testing.assert_allclose(got, want, rtol=0, atol=TOL)
    np.testing.assert_allclose(analysis.predicted_end, np.array(expected["predicted_end"]), rtol=0, atol=TOL)
    assert analysis.predicted_end.dtype == np.float64 and analysis.predicted_end.shape == (expected["n"], 3)
    assert analysis.label == expected["label"]["text"]
    assert analysis.close == expected["close"]
    assert analysis.metrics == expected["metrics"]
    assert analysis.border_indices.tolist() == expected["border_indices"]


@pytest.mark.parametrize("path", PHYSICS[:3] + REFERENCE[:3], ids=lambda p: p.stem)
def test_arrays_and_samples_give_the_same_analysis(path):
    sample = close.load(path)
    from_sample = close.analyze(sample).to_dict()
    assert close.analyze(sample.frames).to_dict() == from_sample
    assert close.analyze(list(sample.frames)).to_dict() == from_sample


def test_frame_range_and_method_as_the_cli():
    path = next(p for p in PHYSICS if "then" in p.stem)  # three frames: two folds
    for args, kwargs in [(["--start", 1], {"start": 1}), (["--end", 1], {"end": 1}), (["--method", "paper"], {"method": "paper"})]:
        assert close.analyze(close.load(path), **kwargs).to_dict() == cli_json("analyze", path, *args)


@pytest.mark.parametrize("path", PHYSICS[:2] + REFERENCE[:2], ids=lambda p: p.stem)
def test_dgli_disk_is_the_clis_start_disk(path):
    expected = cli_json("analyze", path, "--disks")
    sample = close.load(path)
    start = close.dgli_disk(sample.frames[0])
    np.testing.assert_allclose(start, expected["disk_start"], rtol=0, atol=TOL)
    end = close.dgli_disk(sample.frames[-1], reference=sample.frames[0])
    np.testing.assert_allclose(end, expected["disk_end"], rtol=0, atol=TOL)
    n = expected["n"]
    radius, angle = close.disk_layout(n)
    assert start.shape == radius.shape == angle.shape == (n * (n - 1) // 2,)
    assert radius.max() == 1.0 and ((0 <= angle) & (angle < 2 * np.pi)).all()


def test_analyze_many_equals_analyze():
    samples = [close.load(p) for p in SAMPLES[:12]]
    one_by_one = [close.analyze(s).to_dict() for s in samples]
    for threads in (1, 2, None):
        assert [a.to_dict() for a in close.analyze_many(samples, threads=threads)] == one_by_one


def test_evaluate_equals_close_eval():
    folder = FIXTURES / "physics"
    expected = cli_json("eval", folder)
    assert close.evaluate(folder) == expected
    assert close.evaluate(str(folder), threads=1) == expected
    with ThreadPoolExecutor(2) as pool:
        assert close.evaluate(folder, executor=pool) == expected


def test_evaluate_of_samples_equals_close_eval_of_their_files():
    paths = PHYSICS[:4]
    expected = cli_json("eval", *paths)
    assert close.evaluate(paths) == expected
    samples = [close.load(p) for p in paths]

    def without_index(report):
        assert [row.pop("index") for row in report["samples"]] == list(range(len(paths)))
        return report

    assert without_index(close.evaluate(samples)) == expected
    with ThreadPoolExecutor(2) as pool:
        assert without_index(close.evaluate(samples, executor=pool)) == expected


def test_plan_and_interpolate_answer_as_the_cli():
    path = next(p for p in PHYSICS if "half" in p.stem)
    goal = (0.5, 3.6)
    expected = cli_json("plan", path, "--goal", "0.5,3.6")
    sample = close.load(path)
    answer = close.plan(sample, goal)
    assert answer == expected
    assert close.plan(close.analyze(sample), goal) == answer
    motion = close.interpolate(sample.frames[0], (0.0, 3.1), (0.5, 3.6), 7)
    assert motion.shape == (7, sample.frames.shape[1], 3) and motion.dtype == np.float64
    assert np.isfinite(motion).all() and not np.allclose(motion[0], motion[-1])
