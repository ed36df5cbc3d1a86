"""Shared fixtures of the Python tests: the build tree's `tcasim` program and the source tree.
ctest sets TCASIM_BIN and TCASIM_SOURCE_DIR (python/CMakeLists.txt) and PYTHONPATH to the
build tree's package; run by hand:
  PYTHONPATH=build/python TCASIM_BIN=build/bin/tcasim /usr/bin/python3 -m pytest tests/python
"""
import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("TCASIM_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
SCENARIO_DIR = SOURCE_DIR / "validation" / "scenarios"


def scenario_files():
    """Every shipped scenario (not the TCA-only files)."""
    out = []
    for p in sorted(SCENARIO_DIR.glob("*.json")):
        if json.loads(p.read_text()).get("schema") == "tcasim.scenario/1":
            out.append(p)
    return out


@pytest.fixture(scope="session")
def tcasim_bin():
    path = os.environ.get("TCASIM_BIN", str(SOURCE_DIR / "build" / "bin" / "tcasim"))
    if not os.path.exists(path):
        pytest.fail(f"the tcasim program is not at {path} (set TCASIM_BIN)")
    return path


@pytest.fixture(scope="session")
def run_cli(tcasim_bin):
    """Runs `tcasim ARGS...`; returns the CompletedProcess (text)."""

    def run(*args):
        return subprocess.run([tcasim_bin, *map(str, args)], capture_output=True, text=True)

    return run
