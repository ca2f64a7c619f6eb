"""The inputs people have: (N, 2) and (F, N, 2) borders as z = 0, `Sample(...)` checked when
made, `Sample.from_json`, and `.npy`/`.npz` files in `close.load`."""

import json

import numpy as np
import pytest

import close
from conftest import PHYSICS, REFERENCE


def flat(frames):
    """The same frames with every z set to 0 (what an (F, N, 2) input means)."""
    out = np.array(frames, dtype=float)
    out[..., 2] = 0.0
    return out


@pytest.mark.parametrize("path", REFERENCE[:2] + PHYSICS[:2], ids=lambda p: p.stem)
def test_two_columns_are_x_y_on_the_table(path):
    frames = flat(close.load(path).frames)
    expected = close.analyze(frames).to_dict()
    assert close.analyze(frames[..., :2]).to_dict() == expected  # (F, N, 2)
    assert close.analyze([f[:, :2] for f in frames]).to_dict() == expected  # list of (N, 2)
    np.testing.assert_array_equal(close.Sample(frames[..., :2]).frames, frames)
    np.testing.assert_array_equal(close.dgli_disk(frames[0][:, :2]), close.dgli_disk(frames[0]))
    motion = close.interpolate(frames[0][:, :2], (0.0, 3.1), (0.5, 3.6), 3)
    np.testing.assert_array_equal(motion, close.interpolate(frames[0], (0.0, 3.1), (0.5, 3.6), 3))


@pytest.mark.parametrize(
    "frames, message",
    [
        (np.array([[[0.0, 0, 0], [1, 0, 0], [1, np.nan, 0], [0, 1, 0]]]), "non-finite coordinate in frame 0, vertex 2"),
        (np.zeros((1, 3, 3)) + np.arange(3)[:, None], "too few vertices"),
        ([np.eye(4, 3), np.eye(5, 3)], "frame 1 has 5 vertices but frame 0 has 4"),
        (np.zeros((1, 6, 2)), "all vertices coincide"),
        (np.zeros((1, 4, 4)), "expected an (F, N, 3) array"),
    ],
)
def test_a_sample_is_checked_when_made(frames, message):
    with pytest.raises(close.CloseError) as err:
        close.Sample(frames)
    assert message in str(err.value)


def test_from_json_reads_what_to_json_writes():
    sample = close.load(PHYSICS[0])
    text = sample.to_json()
    assert close.Sample.from_json(text) == sample
    assert close.Sample.from_json(text.encode()) == sample
    with pytest.raises(close.CloseError, match="JSON"):
        close.Sample.from_json("{ not json")
    # A border on a line parses, but is refused here as the analysis would refuse it.
    line = json.dumps({"frames": [[[k, 0, 0] for k in range(4)]]})
    with pytest.raises(close.CloseError, match="degenerate border"):
        close.Sample.from_json(line)


def test_npy_and_npz_files_load_as_samples(tmp_path):
    frames = close.load(PHYSICS[0]).frames
    expected = close.analyze(frames).to_dict()
    np.save(tmp_path / "frames.npy", frames)
    np.savez(tmp_path / "sample.npz", frames=frames, other=np.zeros(3))
    np.savez(tmp_path / "one.npz", frames[..., :2])
    for k, frame in enumerate(frames):
        np.save(tmp_path / f"frame{k}.npy", frame)
    loaded = close.load(tmp_path / "frames.npy")
    assert (loaded.name, loaded.category) == ("frames.npy", "upload")
    assert close.analyze(loaded).to_dict() == expected
    assert close.analyze(close.load(tmp_path / "sample.npz")).to_dict() == expected
    assert close.analyze(close.load(*[tmp_path / f"frame{k}.npy" for k in range(len(frames))])).to_dict() == expected
    np.testing.assert_array_equal(close.load(tmp_path / "one.npz").frames, flat(frames))


def test_bad_numpy_files_are_named(tmp_path):
    (tmp_path / "text.npy").write_text("not numpy")
    with pytest.raises(close.CloseError, match="text.npy: not a readable numpy file"):
        close.load(tmp_path / "text.npy")
    np.savez(tmp_path / "two.npz", a=np.zeros(3), b=np.zeros(3))
    with pytest.raises(close.CloseError, match="'frames' array"):
        close.load(tmp_path / "two.npz")
    np.save(tmp_path / "a.npy", np.zeros((2, 4, 3)))
    with pytest.raises(close.CloseError, match="one \\(N, 3\\) or \\(N, 2\\) frame"):
        close.load(tmp_path / "a.npy", tmp_path / "a.npy")
    with pytest.raises(close.CloseError, match="not mixed"):
        close.load(tmp_path / "a.npy", PHYSICS[0])
    with pytest.raises(FileNotFoundError):
        close.load(tmp_path / "missing.npy")
    np.save(tmp_path / "objects.npy", np.array([{"a": 1}], dtype=object), allow_pickle=True)
    with pytest.raises(close.CloseError, match="not a readable numpy file"):
        close.load(tmp_path / "objects.npy")  # no pickles are loaded
