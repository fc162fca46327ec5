"""Shared fixtures: the repository's bundled scenes and the `kepler` command line, whose
outputs the Python package must reproduce."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = sorted((ROOT / "scenes").glob("*.toml"))
# The bundled scenes with the metropolis marked slow: reading its files with third-party
# readers (vpype, ezdxf) takes about a minute; `pytest --slow` runs it too.
SCENES_QUICK = [
    pytest.param(s, id=s.stem, marks=pytest.mark.slow) if s.stem == "metropolis" else
    pytest.param(s, id=s.stem)
    for s in SCENES
]


def pytest_addoption(parser):
    parser.addoption("--slow", action="store_true", help="also run the tests marked slow")


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: a long case, run with --slow")


def pytest_collection_modifyitems(config, items):
    if config.getoption("--slow"):
        return
    skip = pytest.mark.skip(reason="slow: run with --slow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


@pytest.fixture(scope="session")
def cli():
    """The release binary (`KEPLER_BIN`, else target/release/kepler, built if missing)."""
    path = pathlib.Path(os.environ.get("KEPLER_BIN", ROOT / "target" / "release" / "kepler"))
    if not path.exists():
        subprocess.run(["cargo", "build", "--release"], cwd=ROOT, check=True)
    return str(path)
