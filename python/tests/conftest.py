"""Paths the tests share: the checkout's shipped example and the command-line binary."""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EIGHT = ROOT / "data" / "eight_15.csl"


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The CLI built by `cargo build --release` (or `cargo test --release`, as .ci/run runs first);
    `$SLICE2SOLID_BIN` overrides. Missing, the tests that compare with it fail: they do not skip."""
    path = pathlib.Path(os.environ.get("SLICE2SOLID_BIN", ROOT / "target" / "release" / "slice2solid"))
    assert path.is_file(), f"{path} missing: run `cargo build --release` first (or set SLICE2SOLID_BIN)"
    return path


@pytest.fixture(scope="session")
def eight():
    import slice2solid

    sections = slice2solid.read(EIGHT)
    return sections, slice2solid.reconstruct(sections)
