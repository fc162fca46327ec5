"""Shared fixtures: the repository's bundled scenes and the `kepler` command line, whose
outputs the Python package must reproduce."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = sorted((ROOT / "scenes").glob("*.toml"))


@pytest.fixture(scope="session")
def cli():
    """The release binary (`KEPLER_BIN`, else target/release/kepler, built if missing)."""
    path = pathlib.Path(os.environ.get("KEPLER_BIN", ROOT / "target" / "release" / "kepler"))
    if not path.exists():
        subprocess.run(["cargo", "build", "--release"], cwd=ROOT, check=True)
    return str(path)
