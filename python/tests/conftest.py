"""Shared helpers: the repository's fixtures and the `close` command line to compare with.

The CLI is the release binary of this checkout: `$CLOSE_BIN`, else `target/release/close`
at the repository root (`.ci/run` builds it before running this suite).
"""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "tests" / "fixtures"
REFERENCE = sorted((FIXTURES / "reference").glob("*/*.json"))
PHYSICS = sorted((FIXTURES / "physics").glob("*.json"))
STORE = FIXTURES / "vrfolding" / "vr_simulation_folding2_dataset.zarr"


def close_bin() -> Path:
    path = Path(os.environ.get("CLOSE_BIN", ROOT / "target" / "release" / "close"))
    if not path.is_file():
        pytest.fail(f"the close CLI is needed to compare with: set CLOSE_BIN or run `cargo build --release` ({path} not found)")
    return path


def cli(*args) -> subprocess.CompletedProcess:
    """Run `close ARGS...`, capturing its output."""
    return subprocess.run([str(close_bin()), *map(str, args)], capture_output=True, text=True, timeout=600)


def cli_json(*args):
    """`close ARGS... --json`'s object; the command must succeed."""
    done = cli(*args, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def cli_error(*args) -> str:
    """The message of a failing `close ARGS...` (its `error: ` line, without the prefix)."""
    done = cli(*args)
    assert done.returncode != 0, f"close {args} succeeded"
    line = done.stderr.strip().splitlines()[-1]
    assert line.startswith("error: "), done.stderr
    return line[len("error: "):]
