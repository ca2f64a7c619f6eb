"""The type stubs: mypy --strict passes on a typed user's code (tests/typed/example.py) and
fails on code that misuses the API."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent

pytest.importorskip("mypy", reason="mypy is not installed (.ci/run installs it)")


def mypy(*paths):
    return subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir", "/dev/null", *map(str, paths)],
                          capture_output=True, text=True, timeout=600)


def test_the_typed_example_passes_mypy():
    done = mypy(HERE / "typed" / "example.py")
    assert done.returncode == 0, done.stdout + done.stderr


def test_mypy_catches_a_misuse(tmp_path):
    wrong = tmp_path / "wrong.py"
    wrong.write_text("import close\n\nresult: int = close.analyze_many([], threads='2')\n")
    done = mypy(wrong)
    assert done.returncode == 1 and "threads" in done.stdout, done.stdout
