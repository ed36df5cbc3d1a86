"""Shared fixtures of the Python tests: the build tree's `tcasim` program and the source tree.
ctest sets TCASIM_BIN and TCASIM_SOURCE_DIR (python/CMakeLists.txt) and PYTHONPATH to the
build tree's package; run by hand:
  PYTHONPATH=build/python TCASIM_BIN=build/bin/tcasim /usr/bin/python3 -m pytest tests/python
"""
import json
import os
import pathlib
import subprocess
import threading
import time

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


def longest_gap_while(work):
    """Runs work() in another thread while this one ticks; returns (the longest gap between
    ticks during the call [s], the call's duration [s]). With the GIL held by the call, the
    gap is the whole call; released, the operating system's scheduling only."""
    span = {}

    def timed():
        span["start"] = time.perf_counter()
        work()
        span["end"] = time.perf_counter()

    ticks = []
    t = threading.Thread(target=timed)
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
    t.join()
    inside = [span["start"]] + [x for x in ticks if span["start"] < x < span["end"]] + [span["end"]]
    return max(b - a for a, b in zip(inside, inside[1:])), span["end"] - span["start"]
