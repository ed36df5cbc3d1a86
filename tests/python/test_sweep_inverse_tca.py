"""tcasim.sweep, tcasim.inverse, tcasim.grasp and tcasim.tca_curve give the numbers of
`tcasim sweep`, `tcasim inverse`, `tcasim grasp` and `tcasim tca`."""
import csv
import io
import json

import numpy as np
import pytest

import tcasim
from conftest import SCENARIO_DIR


def read_csv(text):
    rows = list(csv.DictReader(io.StringIO(text)))
    return {k: [r[k] for r in rows] for k in rows[0]}


def sweep_cell(v, name):
    """A Python sweep value as `tcasim sweep` prints it (apps/cmd_solve.cpp)."""
    if isinstance(v, (bool, np.bool_)):
        return "1" if v else "0"
    if name == "iterations":
        return str(int(v))
    if np.isnan(v):
        return ""
    if name == "residual":
        return f"{v:.6e}"
    return f"{v:.12e}"


@pytest.mark.parametrize("method", ["cosserat", "fe"])
def test_temperature_sweep_matches_the_cli_csv(method, run_cli):
    scenario = SCENARIO_DIR / "square-manipulator-25C.json"
    cli = run_cli("sweep", scenario, "--actuator", "u-tca", "--temperatures-degC", "25:45:10",
                  "--method", method, "--elements", "8")
    assert cli.returncode == 0, cli.stderr
    expected = read_csv(cli.stdout)
    got = tcasim.sweep(scenario, "u-tca", temperatures_degC=[25, 35, 45], method=method,
                       elements=8)
    assert [k for k in got if k != "status"] == list(expected)
    assert got["status"] == ["converged"] * 3
    for name, column in expected.items():
        if name == "temperature_degC":
            assert [f"{v:g}" for v in got[name]] == column
        else:
            assert [sweep_cell(v, name) for v in got[name]] == column, name


def test_tension_sweep_matches_the_cli_csv(run_cli):
    scenario = SCENARIO_DIR / "steel-4-tendon.json"
    cli = run_cli("sweep", scenario, "--actuator", "t0", "--tensions-N", "0:10:5")
    assert cli.returncode == 0, cli.stderr
    expected = read_csv(cli.stdout)
    got = tcasim.sweep(scenario, "t0", tensions_N=np.array([0.0, 5.0, 10.0]))
    for name, column in expected.items():
        if name != "tension_N":
            assert [sweep_cell(v, name) for v in got[name]] == column, name


def test_inverse_matches_the_cli_document(run_cli, tmp_path):
    scenario = SCENARIO_DIR / "square-manipulator-25C.json"
    target = [-1.962027285920e-03, 0, 3.992439219707e-02]
    out = tmp_path / "inv.json"
    cli = run_cli("inverse", scenario, "--target-m", ",".join(map(repr, target)), "--out", out)
    assert cli.returncode == 0, cli.stderr
    got = tcasim.inverse(scenario, target)
    assert got == json.loads(out.read_text())
    assert got["converged"] and got["actuators"][0]["coils_closed"] is False


def test_inverse_reaches_a_target_resting_on_an_obstacle(run_cli, tmp_path):
    # The TCA finger of the contact suite curls onto its peg above about 88 degC: the tip of
    # the forward sweep point at 100 degC (in contact) is the target, reached from ambient.
    scenario = SCENARIO_DIR / "contact" / "tca-finger-cylinder.json"
    sweep = run_cli("sweep", scenario, "--actuator", "u-tca", "--temperatures-degC", "100:100:1")
    assert sweep.returncode == 0, sweep.stderr
    row = read_csv(sweep.stdout)
    assert row["peg_in_contact"] == ["1"]
    target = [float(row[f"tip_{c}_m"][0]) for c in "xyz"]
    out = tmp_path / "inv.json"
    cli = run_cli("inverse", scenario, "--target-m", ",".join(map(repr, target)), "--out", out)
    assert cli.returncode == 0, cli.stderr
    got = tcasim.inverse(scenario, target)
    assert got == json.loads(out.read_text())
    assert got["converged"]
    # The tip Jacobian by differences of contact solves (about 1e-5 relative) still lands on
    # the target; the temperature is the sweep's to the tip tolerance over dp/dT.
    assert abs(got["actuators"][0]["temperature_degC"] - 100.0) < 1e-5
    assert got["contacts"][0]["regions"] and got["contact_model"] == "frictionless"


def test_grasp_matches_the_cli_document(run_cli, tmp_path):
    scenario = SCENARIO_DIR / "gripper-finger.json"
    out = tmp_path / "grasp.json"
    cli = run_cli("grasp", scenario, "--mass-g", "10", "--friction", "0.5", "--fingers", "2",
                  "--out", out)
    assert cli.returncode == 0, cli.stderr
    got = tcasim.grasp(scenario, mass_g=10, friction=0.5, fingers=2)
    assert got == json.loads(out.read_text())


def test_tca_curve_matches_the_cli_table(run_cli):
    source = SCENARIO_DIR / "circular-manipulator.json"
    cli = run_cli("tca", source, "--load-g", "7.5", "--temperatures-degC", "25:160:15")
    assert cli.returncode == 0, cli.stderr
    expected = read_csv(cli.stdout)
    temps = np.arange(25.0, 161.0, 15.0)
    got = tcasim.tca_curve(source, temps, load_g=7.5)
    # `tcasim tca` prints shortest round-trip numbers: equal text is equal doubles.
    for name in ("elongation_m", "tension_N", "pitch_angle_deg"):
        assert [float(v) for v in expected[name]] == list(got[name]), name
    assert [v == "1" for v in expected["coils_closed"]] == list(got["coils_closed"])
    # The same TCA from the scenario object.
    again = tcasim.tca_curve(tcasim.load_scenario(source), temps, load_g=7.5)
    np.testing.assert_array_equal(again["elongation_m"], got["elongation_m"])


def test_sweep_threads_give_the_serial_numbers():
    scenario = SCENARIO_DIR / "circular-manipulator.json"
    temps = [30, 40, 50, 60, 70, 80, 90]
    serial = tcasim.sweep(scenario, "tca", temperatures_degC=temps, chunk=2)
    threads = tcasim.sweep(scenario, "tca", temperatures_degC=temps, chunk=2, jobs=3)
    assert list(serial) == list(threads)
    for k in serial:
        assert list(serial[k]) == list(threads[k]), k
    # A chunk starts cold: its first point equals a single-point sweep.
    alone = tcasim.sweep(scenario, "tca", temperatures_degC=[50])
    assert alone["tip_x_m"][0] == serial["tip_x_m"][2]
    with pytest.raises(tcasim.InputError) as e:
        tcasim.sweep(scenario, "tca", temperatures_degC=temps, jobs=0)
    assert e.value.key == "jobs"


def test_tca_curve_names_its_arguments_in_errors():
    # The selection of `tcasim tca` (rod::select_tca) under the Python argument names.
    source = SCENARIO_DIR / "fig5-tcas.json"
    with pytest.raises(tcasim.InputError) as e:
        tcasim.tca_curve(source, [30], load_g=5)
    assert (e.value.key, e.value.value) == ("tca", "(missing)")
    assert "defines 2 TCAs: four-thread, three-thread" in e.value.rule
    with pytest.raises(tcasim.InputError) as e:
        tcasim.tca_curve(source, [30], load_g=5, tca="two-thread")
    assert e.value.key == "tca" and "(it has: four-thread, three-thread)" in e.value.rule
    with pytest.raises(tcasim.InputError) as e:
        tcasim.tca_curve(source, [30], load_g=5, tca="three-thread", f12_form="exact")
    assert (e.value.key, e.value.rule) == ("f12_form", "must be paper or castigliano")
    with pytest.raises(tcasim.InputError) as e:
        tcasim.tca_curve(source, [30], load_g=5, tca="three-thread", material="no-such-material")
    assert e.value.key == "material"


def test_tca_curve_with_a_measured_fiber_diameter_matches_the_cli(run_cli):
    # validation/scenarios/liuyang-monocoil-tcas.json: the open-coil monocoil with its measured
    # fiber (docs/conventions.md "Measured fiber diameter") and the same TCA with the paper's d0.
    source = SCENARIO_DIR / "liuyang-monocoil-tcas.json"
    cli = run_cli("tca", source, "--tca", "measured", "--tension-N", "1", "--temperatures-degC",
                  "25:120:95")
    assert cli.returncode == 0, cli.stderr
    expected = read_csv(cli.stdout)
    got = tcasim.tca_curve(source, [25.0, 120.0], tension_N=1.0, tca="measured")
    for name in ("elongation_m", "tension_N", "pitch_angle_deg"):
        assert [float(v) for v in expected[name]] == list(got[name]), name
    # The paper's d0 = 2 D L / l = 1.22 mm makes the 0.74 mm fiber's coil far stiffer.
    paper = tcasim.tca_curve(source, [25.0], tension_N=1.0, tca="paper-d0")
    assert got["elongation_m"][0] > 5.0 * paper["elongation_m"][0]


def test_scenario_with_a_measured_fiber_diameter_solves_and_bad_geometry_is_named():
    d = json.loads((SCENARIO_DIR / "circular-manipulator.json").read_text())
    t = d["tcas"]["manipulator-tca"]
    t["fiber_diameter_m"] = 0.0004  # open coil: 36.5 coils of pitch 1.1 mm
    sc = tcasim.load_scenario(d)
    assert sc.to_dict()["tcas"]["manipulator-tca"]["fiber_diameter_m"] == 0.0004
    r = tcasim.solve(sc)
    assert r.converged
    # Over-determined and disagreeing: 20 coils is not the 15 deg helix of mean diameter 1.3 mm.
    t["coil_count"] = 20
    with pytest.raises(tcasim.InputError) as e:
        tcasim.load_scenario(d)
    assert e.value.key == "tcas.manipulator-tca.coil_count"
    assert "disagrees with pitch_angle_deg" in e.value.rule
    del t["coil_count"]
    t["fiber_diameter_m"] = 0.001  # thicker than half the 1.7 mm coil
    with pytest.raises(tcasim.InputError) as e:
        tcasim.load_scenario(d)
    assert e.value.key == "tcas.manipulator-tca.fiber_diameter_m"
