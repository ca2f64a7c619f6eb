"""What a notebook user reads: docstrings that state the conventions, and type stubs."""

from pathlib import Path

import close


def test_help_of_analyze_states_the_conventions():
    doc = close.analyze.__doc__
    for words in ["radians", "vertex k sits at\nangle 2πk/N", "anticlockwise from f1 to f2", "close analyze --json", "CloseError"]:
        assert words.replace("\n", " ") in doc.replace("\n", " "), words


def test_every_public_name_is_documented():
    for name in close.__all__:
        assert getattr(close, name).__doc__, name
    assert "2πk/N" in close.__doc__ and "anticlockwise" in close.Analysis.__doc__


def test_the_package_ships_type_stubs():
    folder = Path(close.__file__).parent
    assert (folder / "py.typed").is_file()
    stubs = (folder / "__init__.pyi").read_text()
    for name in close.__all__:
        assert name in stubs, name
    assert "def open" in (folder / "vrfolding.pyi").read_text()
