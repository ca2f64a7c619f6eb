"""`python -m close analyze|eval|plan`: the CLI's flags, and its output (the same JSON, the
same table and plan text, the same errors)."""

import json
import subprocess
import sys

import pytest

from conftest import FIXTURES, PHYSICS, REFERENCE, cli, cli_error, cli_json


def py(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "close", *map(str, args)], capture_output=True, text=True, timeout=600)


def py_json(*args):
    done = py(*args)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


TWO_FOLDS = next(p for p in PHYSICS if "then" in p.stem)


@pytest.mark.parametrize(
    "args",
    [
        [REFERENCE[0]],
        [PHYSICS[0], "--disks"],
        [TWO_FOLDS, "--start", 1],
        [TWO_FOLDS, "--end", 1, "--method", "paper"],
    ],
    ids=["reference", "disks", "start", "end-paper"],
)
def test_analyze_prints_the_clis_json(args):
    assert py_json("analyze", *args, "--json") == cli_json("analyze", *args)


def test_eval_prints_the_clis_json_and_table():
    folder = FIXTURES / "physics"
    assert py_json("eval", folder, "--json") == cli_json("eval", folder)
    for args in [[folder], [folder, "--method", "paper"]]:
        ours, theirs = py("eval", *args), cli("eval", *args)
        assert ours.returncode == theirs.returncode == 0, ours.stderr
        assert ours.stdout == theirs.stdout


def test_eval_builtin_as_the_cli():
    assert py_json("eval", "--builtin", "--json") == cli_json("eval", "--builtin")


def test_plan_prints_the_clis_json_and_text():
    path = next(p for p in PHYSICS if "half" in p.stem)
    for goal in ["0.5,3.6", "0.1,2", "0.5,3.6;1.2,4.0"]:
        assert py_json("plan", path, "--goal", goal, "--json") == cli_json("plan", path, "--goal", goal)
        ours, theirs = py("plan", path, "--goal", goal), cli("plan", path, "--goal", goal)
        assert ours.returncode == theirs.returncode == 0, ours.stderr
        assert ours.stdout == theirs.stdout


def test_errors_are_the_clis(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{ not json")
    done = py("analyze", bad, "--json")
    assert done.returncode == 1
    assert done.stderr.strip().splitlines()[-1] == f"error: {cli_error('analyze', bad)}"
    missing = py("analyze", tmp_path / "missing.json")
    assert missing.returncode == 1 and "missing.json" in missing.stderr and missing.stderr.startswith("error: ")
    empty = tmp_path / "empty"
    empty.mkdir()
    for args in [["plan", PHYSICS[0], "--goal", "1"], ["eval", empty]]:
        ours, theirs = py(*args), cli(*args)
        assert ours.returncode == theirs.returncode == 2, (args, ours.stderr)
        assert ours.stderr.strip().splitlines()[-1] == theirs.stderr.strip().splitlines()[-1]
    assert py("frobnicate").returncode == 2
