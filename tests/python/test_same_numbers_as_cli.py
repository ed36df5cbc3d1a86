"""tcasim.solve gives the result file of `tcasim solve`, to the last digit, on every shipped
scenario with both methods (the wall time aside), and its attributes hold the same numbers."""
import json
import re

import numpy as np
import pytest

import tcasim
from conftest import scenario_files

WALL_TIME = re.compile(r'^  "wall_time_s": .*\n', re.M)

CASES = [(p, m) for p in scenario_files() for m in ("cosserat", "fe")]


def strip_wall_time(d):
    d = dict(d)
    d.pop("wall_time_s")
    return d


@pytest.mark.parametrize("path,method", CASES, ids=[f"{p.stem}-{m}" for p, m in CASES])
def test_result_equals_the_cli_result_file(path, method, run_cli, tmp_path):
    out = tmp_path / "result.json"
    cli = run_cli("solve", path, "--method", method, "--out", out)
    assert cli.returncode in (0, 4), cli.stderr
    text = out.read_text()
    r = tcasim.solve(str(path), method=method, check=False)
    assert r.converged == (cli.returncode == 0)
    # The text of the file, byte for byte, but for the wall time.
    assert WALL_TIME.sub("", r.to_json()) == WALL_TIME.sub("", text)
    # The dict is the parsed file; solving the parsed file as a dict gives the same numbers.
    file_dict = strip_wall_time(json.loads(text))
    assert strip_wall_time(r.to_dict()) == file_dict
    r2 = tcasim.solve(json.loads(path.read_text()), method=method, check=False)
    assert strip_wall_time(r2.to_dict()) == file_dict
    # The attributes carry the file's numbers exactly.
    assert r.scenario == file_dict["scenario"] and r.method == method
    assert r.status == file_dict["status"] and r.iterations == file_dict["iterations"]
    assert r.residual == file_dict["residual"]
    assert r.discretization == file_dict["discretization"]
    assert r.characteristic_force_N == file_dict["characteristic_force_N"]
    np.testing.assert_array_equal(r.tip_position_m, file_dict["tip"]["position_m"])
    np.testing.assert_array_equal(r.tip_rotation, file_dict["tip"]["rotation"])
    np.testing.assert_array_equal(r.centerline_s_m, file_dict["centerline"]["s_m"])
    np.testing.assert_array_equal(r.centerline_position_m, file_dict["centerline"]["position_m"])
    assert r.centerline_rotation.shape == (len(r.centerline_s_m), 3, 3)
    assert r.actuators == file_dict["actuators"]
    assert r.bending_radius_m == file_dict["bending_radius_m"]
    if "tip_reaction_force_N" in file_dict:
        np.testing.assert_array_equal(r.tip_reaction_force_N, file_dict["tip_reaction_force_N"])
    else:
        assert r.tip_reaction_force_N is None
    assert r.message == file_dict.get("message", "")
    assert r["tip"] == file_dict["tip"]


# Options reach the solvers as the flags do.
OPTION_CASES = [
    ("circular-manipulator", {"scheme": "rk8", "steps": 6}, ["--scheme", "rk8", "--steps", "6"]),
    ("circular-manipulator", {"rtol": 1e-8}, ["--rtol", "1e-8"]),
    ("circular-manipulator", {"no_planar": True, "steps": 40}, ["--no-planar", "--steps", "40"]),
    ("steel-4-tendon", {"method": "fe", "elements": 8, "order": 1, "integration": "full",
                        "linear_solver": "umfpack"},
     ["--method", "fe", "--elements", "8", "--order", "1", "--integration", "full",
      "--linear-solver", "umfpack"]),
]


@pytest.mark.parametrize("name,kwargs,flags", OPTION_CASES, ids=[str(c[2]) for c in OPTION_CASES])
def test_options_mirror_the_cli_flags(name, kwargs, flags, run_cli, tmp_path):
    from conftest import SCENARIO_DIR

    scenario = SCENARIO_DIR / f"{name}.json"
    out = tmp_path / "r.json"
    cli = run_cli("solve", scenario, *flags, "--out", out)
    assert cli.returncode == 0, cli.stderr
    kwargs = dict(kwargs)
    method = kwargs.pop("method", "cosserat")
    r = tcasim.solve(scenario, method, **kwargs)
    assert WALL_TIME.sub("", r.to_json()) == WALL_TIME.sub("", out.read_text())


def test_vtk_and_shape_csv_are_the_cli_files(run_cli, tmp_path):
    from conftest import SCENARIO_DIR

    scenario = SCENARIO_DIR / "circular-manipulator.json"
    cli = run_cli("solve", scenario, "--vtk", tmp_path / "a.vtp", "--shape-csv", tmp_path / "a.csv",
                  "--out", tmp_path / "a.json")
    assert cli.returncode == 0, cli.stderr
    tcasim.solve(scenario, vtk=tmp_path / "b.vtp", shape_csv=tmp_path / "b.csv")
    assert (tmp_path / "a.vtp").read_text() == (tmp_path / "b.vtp").read_text()
    assert (tmp_path / "a.csv").read_text() == (tmp_path / "b.csv").read_text()
