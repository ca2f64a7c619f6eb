"""Conventions stated and kept: corner numbers (1-based) with their vertex indices beside
them in the label and the plan; a clockwise input's folds in its own vertex order; the units
of the metrics and of the angle errors; the population variance."""

import math

import numpy as np
import pytest

import close
from conftest import FIXTURES, PHYSICS, REFERENCE, cli, cli_json

FOLDED = [p for p in REFERENCE + PHYSICS if "nofold" not in str(p)]


@pytest.mark.parametrize("path", FOLDED[:6] + PHYSICS[-3:], ids=lambda p: p.stem)
def test_each_corner_number_has_its_vertex_beside_it(path):
    analysis = close.analyze(close.load(path))
    vertices = analysis.corner_vertices.tolist()
    assert len(vertices) == len(analysis.corners)
    # Corner k (1-based) sits at angle corners[k - 1] = 2π·vertex/N.
    for angle, vertex in zip(analysis.corners, vertices):
        assert math.isclose(angle, 2 * math.pi * vertex / analysis.n, abs_tol=1e-12)
    label = analysis.to_dict()["label"]
    for fold in label["folds"]:
        assert fold["folded_corner_vertices"] == [vertices[c - 1] for c in fold["folded_corners"]]
        assert fold["corner_vertices_on_fold_line"] == [vertices[c - 1] for c in fold["corners_on_fold_line"]]
        for side in fold["cut_sides"] + [s for c in fold["corner_sides"] for s in (c["before"], c["after"])]:
            assert (side["from_vertex"], side["to_vertex"]) == (vertices[side["from_corner"] - 1], vertices[side["to_corner"] - 1])
        for c in fold["corner_sides"]:
            assert c["vertex"] == vertices[c["corner"] - 1]
    indices = analysis.border_indices.tolist()
    for step in close.plan(analysis, (0.5, 3.6))["steps"]:
        # The plan's vertices are the input's (as its picks'), through border_indices.
        assert step["corner_vertices"] == [indices[vertices[c - 1]] for c in step["corners"]]
        assert all(p["vertex"] in step["corner_vertices"] for p in step["picks"]) or not step["corners"]


def test_a_clockwise_inputs_folds_in_its_own_order():
    path = next(p for p in PHYSICS if "half" in p.stem)
    frames = close.load(path).frames
    n = frames.shape[1]
    anticlockwise = close.analyze(frames)
    # The same border listed clockwise from vertex 0: input vertex i is vertex (n − i) mod n.
    order = [(n - i) % n for i in range(n)]
    with pytest.warns(close.CloseWarning, match="clockwise"):
        clockwise = close.analyze(frames[:, order])
    assert clockwise.reversed and not anticlockwise.reversed
    # The analysis's own (anticlockwise) order is the same either way.
    np.testing.assert_allclose(clockwise.folds, anticlockwise.folds, rtol=0, atol=1e-12)
    assert anticlockwise.input_folds == anticlockwise.folds
    # In the caller's order the angle f is 2π − f, and the folded side runs the other way.
    for (f1, f2), (g1, g2) in zip(anticlockwise.folds, clockwise.input_folds):
        assert g1 == pytest.approx((2 * math.pi - f2) % (2 * math.pi), abs=1e-9)
        assert g2 == pytest.approx((2 * math.pi - f1) % (2 * math.pi), abs=1e-9)


def test_a_mesh_sample_has_no_input_order(tmp_path):
    # A 4 × 4 grid of vertices, two triangles per cell: its border is found, not given.
    vertices = [f"v {x} {y} 0" for y in range(4) for x in range(4)]
    faces = []
    for y in range(3):
        for x in range(3):
            a = 4 * y + x + 1
            faces += [f"f {a} {a + 1} {a + 5}", f"f {a} {a + 5} {a + 4}"]
    (tmp_path / "grid.obj").write_text("\n".join(vertices + faces) + "\n")
    analysis = close.analyze(close.load(tmp_path / "grid.obj", tmp_path / "grid.obj"))
    assert analysis.to_dict()["border_source"] != "border"
    assert analysis.input_folds is None


def test_metrics_are_in_start_radii():
    path = next(p for p in PHYSICS if "half" in p.stem)
    sample = close.load(path)
    analysis = close.analyze(sample)
    # Scaling the cloth (and moving it) changes no metric: they are in units of the start
    # frame's farthest-vertex radius.
    moved = close.analyze(sample.frames * 7.5 + np.array([3.0, -2.0, 0.0]))
    assert moved.metrics == pytest.approx(analysis.metrics, rel=1e-9, abs=1e-12)
    for word in ["normalised units", "farthest"]:
        assert word in close.__doc__.replace("\n", " ")
    assert "farthest vertex from its centroid is at distance 1" in close.evaluate.__doc__.replace("\n    ", " ")


def test_evaluate_states_its_units_and_keeps_them():
    folder = FIXTURES / "physics"
    report = close.evaluate(folder)
    overall = report["overall"]
    # The report says its units: every angle in radians, every length normalised.
    assert report["units"] == {"angle": "rad", "length": "normalised"}
    rows = [r for r in report["samples"] if r.get("angle_error")]
    assert rows, "the physics fixtures have truth"
    # f1_error is in radians in the JSON: its mean is the mean of the rows' radian errors.
    errors = np.array([r["angle_error"][0] for r in rows])
    assert overall["f1_error"]["mean"] == pytest.approx(errors.mean(), rel=1e-12)
    # var is the population variance (divided by the count).
    assert overall["f1_error"]["var"] == pytest.approx(errors.var(ddof=0), rel=1e-9)
    rmse = np.array([r["rmse"] for r in report["samples"] if r.get("rmse") is not None])
    assert overall["rmse"]["var"] == pytest.approx(rmse.var(ddof=0), rel=1e-9)
    # The table prints the same mean in degrees, under a header that says so.
    table = cli("eval", folder).stdout.splitlines()
    last = next(line for line in table if line.startswith("overall")).split()
    assert "f1 err°" in table[0] and "f2 err°" in table[0]
    assert last[0] == "overall" and float(last[-2]) == pytest.approx(math.degrees(overall["f1_error"]["mean"]), abs=1e-4)
    doc = close.evaluate.__doc__.replace("\n    ", " ")
    assert "radians here and in the JSON" in doc and "population variance" in doc
    assert report == cli_json("eval", folder)
