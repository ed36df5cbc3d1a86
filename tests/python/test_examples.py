"""The examples of examples/python run and say what they found (small settings)."""
import os
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"


def run(name, *args):
    p = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)],
                       capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def test_temperature_sweep_writes_its_plot(tmp_path):
    out = run("temperature_sweep.py", "--out", tmp_path, "--step-degC", 25)
    assert "all converged: True" in out
    png = tmp_path / "temperature_sweep.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_inverse_target_reaches_the_target():
    out = run("inverse_target.py")
    assert "inverse: converged" in out and "forward check" in out


def test_design_study_writes_its_table(tmp_path):
    pytest.importorskip("dask.distributed")
    csv = tmp_path / "study.csv"
    out = run("design_study.py", "--out", csv, "--threads", "--points", 2)
    assert "8 points, 0 failed" in out
    assert len(csv.read_text().splitlines()) == 9


def test_voltage_step_writes_its_plot_and_trajectory(tmp_path):
    out = run("voltage_step.py", "--out", tmp_path, "--duration-s", 0.2, "--dt-s", 0.05)
    assert "5 rows to t = 0.2 s, converged" in out
    assert (tmp_path / "voltage_step.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "voltage_step.csv").read_text().startswith("t_s,tip_x_m,")
