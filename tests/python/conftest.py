"""The suite runs against an installed tree (scripts/install-check): SWATH_TEST_PREFIX is its
prefix, whose bin/swath is the program the module is compared with; the source tree (for the
example areas) is found from this file."""
import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def prefix():
    value = os.environ.get("SWATH_TEST_PREFIX")
    if not value:
        pytest.fail("SWATH_TEST_PREFIX is not set: run the suite through scripts/install-check")
    return Path(value)


@pytest.fixture(scope="session")
def cli(prefix):
    """Runs the installed `swath` with ARGS in DIR; returns the CompletedProcess."""
    def run(args, cwd=SOURCE):
        return subprocess.run([str(prefix / "bin" / "swath")] + [str(a) for a in args], cwd=cwd,
                              capture_output=True, text=True)
    return run


@pytest.fixture(autouse=True)
def in_source_tree(monkeypatch):
    # The examples' paths are relative to the source tree, as in the docs.
    monkeypatch.chdir(SOURCE)
