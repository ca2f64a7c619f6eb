"""The package installs without Rust: `.ci/run` builds the abi3 wheel (`maturin build
--release`), installs that wheel into a fresh venv whose PATH has no cargo or rustc, and runs
this suite there with CLOSE_WHEEL_CHECK=1. This test checks that it is so: the module comes
from an installed abi3 wheel (not a source build or an editable checkout), and no Rust
toolchain was there to build one."""

import importlib.metadata
import os
import shutil
from pathlib import Path

import pytest

import close

if os.environ.get("CLOSE_WHEEL_CHECK") != "1":
    pytest.skip("set by .ci/run, which installs the built wheel in a venv without Rust (CLOSE_WHEEL_CHECK=1)", allow_module_level=True)


def test_no_rust_toolchain_is_on_path():
    assert shutil.which("cargo") is None and shutil.which("rustc") is None, os.environ["PATH"]


def test_the_module_comes_from_an_installed_abi3_wheel():
    dist = importlib.metadata.distribution("close-cloth")
    wheel = dist.read_text("WHEEL") or ""
    assert "Root-Is-Purelib: false" in wheel
    tags = [line.split(": ", 1)[1] for line in wheel.splitlines() if line.startswith("Tag: ")]
    assert tags and all("-abi3-" in t and t.startswith("cp39-") for t in tags), tags
    # Installed into site-packages, not an editable pointer at this checkout.
    package = Path(close.__file__).resolve().parent
    assert "site-packages" in package.parts, package
    assert not (dist.read_text("direct_url.json") or "").count('"editable": true')
    assert any(p.name.startswith("_close") and p.suffix in (".so", ".pyd") for p in package.iterdir())
