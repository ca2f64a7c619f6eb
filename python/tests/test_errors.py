"""Every error path: bad data is `close.CloseError` (a ValueError) with the CLI's message, a
missing file `FileNotFoundError` (a folder `IsADirectoryError`), a FIFO or a file over the
readers' cap refused unread, the server's limits hold, and a Rust panic is an exception."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import close
from conftest import FIXTURES, STORE, cli_error

SQUARE = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])


def test_close_error_is_a_value_error():
    assert issubclass(close.CloseError, ValueError)


BAD_FILES = {
    "not_json.json": "{ not json",
    "no_frames.json": json.dumps({"name": "x", "frames": []}),
    "nan.json": '{"frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]], "extra": 1}'.replace("[1,1,0]", "[1,NaN,0]"),
    "three.json": json.dumps({"frames": [[[0, 0, 0], [1, 0, 0], [1, 1, 0]]]}),
    "coincide.json": json.dumps({"frames": [[[1, 1, 1]] * 5]}),
    "mismatch.json": json.dumps({"frames": [SQUARE.tolist(), SQUARE[:3].tolist()]}),
    "line.json": json.dumps({"frames": [[[0, 0, 0], [1, 1, 0], [2, 2, 0], [3, 3, 0]]]}),
    "words.txt": "a b c\n",
    "short.csv": "0,0,0\n1,0,0\n",
    "broken.obj": "v 0 0 0\nf 1 2 3\n",
    "broken.ply": "ply\nformat ascii 1.0\nelement vertex 2\n",
    "unknown.xyzw": "0 0 0\n",
    "empty.txt": "",
}


@pytest.mark.parametrize("name", sorted(BAD_FILES))
def test_bad_files_raise_the_clis_message(tmp_path, name):
    path = tmp_path / name
    path.write_text(BAD_FILES[name])
    with pytest.raises(close.CloseError) as err:
        close.analyze(close.load(path))
    assert str(err.value) == cli_error("analyze", path)


@pytest.mark.parametrize("name", ["open_border.mat", "wrong_names.mat"])
def test_bad_mat_files_raise_the_clis_message(name):
    path = FIXTURES / "formats" / name
    with pytest.raises(close.CloseError) as err:
        close.analyze(close.load(path))
    assert str(err.value) == cli_error("analyze", path)


def test_frames_out_of_range_raise_the_clis_message():
    path = sorted((FIXTURES / "physics").glob("*.json"))[0]
    for args, kwargs in [(["--start", 5], {"start": 5}), (["--start", 1, "--end", 0], {"start": 1, "end": 0})]:
        with pytest.raises(close.CloseError) as err:
            close.analyze(close.load(path), **kwargs)
        assert str(err.value) == cli_error("analyze", path, *args)


def test_a_missing_file_is_file_not_found(tmp_path):
    missing = tmp_path / "nowhere.json"
    with pytest.raises(FileNotFoundError) as err:
        close.load(missing)
    assert err.value.filename == str(missing)
    with pytest.raises(FileNotFoundError):
        close.evaluate(missing)
    with pytest.raises(FileNotFoundError):
        close.vrfolding.open(tmp_path / "no_store.zarr")


def test_a_fifo_is_refused_at_once_as_the_cli_refuses_it(tmp_path):
    # No writer ever opens these: a blocking open would never return. The reader opens
    # non-blocking and refuses what is not a regular file, before reading a byte.
    for name in ["pipe.json", "pipe.npy"]:
        fifo = tmp_path / name
        os.mkfifo(fifo)
        with pytest.raises(close.CloseError) as err:
            close.load(fifo)
        assert str(err.value) == f"{fifo}: not a regular file (a FIFO, device or socket is never read)"
    assert str(err.value) == cli_error("analyze", fifo)


def test_a_file_over_the_readers_cap_is_refused_unread(tmp_path):
    # Sparse: 64 MiB and one byte long, not one byte on disk.
    for name in ["large.csv", "large.npy"]:
        large = tmp_path / name
        with open(large, "wb") as f:
            f.truncate(64 * 1024 * 1024 + 1)
        with pytest.raises(close.CloseError) as err:
            close.load(large)
        assert str(err.value).startswith(f"{name}: input too large: 67108865 bytes in one file"), err.value
    assert str(err.value) == cli_error("analyze", large)


def test_a_folder_is_is_a_directory_error(tmp_path):
    for path in [tmp_path, tmp_path / "frames.npy"]:
        path.mkdir(exist_ok=True)
        with pytest.raises(IsADirectoryError) as err:
            close.load(path)
        assert err.value.filename == str(path)


def test_a_store_is_not_a_sample():
    with pytest.raises(close.CloseError, match="close.vrfolding.open"):
        close.load(STORE)


def test_a_bad_store_is_a_close_error():
    with pytest.raises(close.CloseError, match="VR-Folding store"):
        close.vrfolding.open(FIXTURES / "formats")


@pytest.mark.parametrize(
    "frames, message",
    [
        (np.zeros((2, 4)), "expected an (F, N, 3) array"),
        ([np.zeros((4, 4))], "frame 0: expected an (N, 3) array"),
        ([SQUARE, SQUARE[:3]], "frame 1 has 3 vertices but frame 0 has 4"),
        (np.array([SQUARE, SQUARE * np.nan]), "non-finite coordinate in frame 1, vertex 0"),
        (SQUARE[None, :3], "too few vertices"),
        (np.zeros((1, 5, 3)), "degenerate border in frame 0: all vertices coincide"),
        (np.zeros((0, 4, 3)), "the sample has no frame"),
        ([["a", "b", "c"]], "not an array of numbers"),
    ],
)
def test_bad_arrays_are_close_errors(frames, message):
    with pytest.raises(close.CloseError) as err:
        close.analyze(frames)
    assert message in str(err.value)


def test_bad_arguments_are_close_errors():
    with pytest.raises(close.CloseError, match="unknown method"):
        close.analyze(np.array([SQUARE, SQUARE]), method="magic")
    with pytest.raises(close.CloseError, match="threads must be at least 1"):
        close.analyze_many([np.array([SQUARE, SQUARE])], threads=0)
    with pytest.raises(close.CloseError, match="item 1: non-finite"):
        close.analyze_many([np.array([SQUARE, SQUARE]), np.array([SQUARE * np.nan])])
    with pytest.raises(close.CloseError, match="not finite"):
        close.plan(np.array([SQUARE, SQUARE]), (float("nan"), 1.0))
    with pytest.raises(close.CloseError, match="steps"):
        close.interpolate(SQUARE, (0.0, 3.1), (0.5, 3.6), 1)
    with pytest.raises(close.CloseError, match="4 to 5000 edges"):
        close.disk_layout(3)
    with pytest.raises(close.CloseError, match="truth"):
        close.Sample(np.array([SQUARE]), truth={"folds": "no"})


def test_the_servers_limits_hold():
    # Over the cell budget (frames × N² > 10⁸): refused before any disk is computed.
    with pytest.raises(close.CloseError, match="too much work"):
        close.analyze(np.random.default_rng(0).random((5, 5000, 3)))
    # More frames or vertices than a border may have.
    with pytest.raises(close.CloseError, match="input too large: 1001 frames"):
        close.analyze(np.zeros((1001, 4, 3)))
    with pytest.raises(close.CloseError, match="input too large"):
        close.dgli_disk(np.zeros((5002, 3)))
    # Over the interpolation budget (vertices × steps > 2·10⁶).
    with pytest.raises(close.CloseError, match="too much work"):
        close.interpolate(np.zeros((5000, 3)), (0.0, 3.1), (0.5, 3.6), 401)


def test_a_rust_panic_is_an_exception_not_an_abort():
    code = (
        "import close._close as c\n"
        "try:\n"
        "    c._panic_for_tests()\n"
        "except BaseException as e:\n"
        "    print(type(e).__name__)\n"
        "print('still alive')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["PanicException", "still", "alive"]
