"""tcasim.simulate gives the trajectory CSV of `tcasim simulate`, to the last digit, with both
methods; its options are the command's flags; a failed step keeps the rows before it."""
import json
import math

import numpy as np
import pytest

import tcasim
from conftest import SCENARIO_DIR, longest_gap_while

DYNAMIC = SCENARIO_DIR / "dynamic"

# (scenario, method, options as keywords): short runs (a few steps each).
CASES = [
    (DYNAMIC / "manipulator-voltage-step.json", "cosserat", {}),
    (DYNAMIC / "manipulator-voltage-step.json", "fe", {"elements": 8}),
    (DYNAMIC / "steel-4-tendon-pull.json", "cosserat", {"output_every": 2}),
    (DYNAMIC / "steel-4-tendon-pull.json", "fe", {"order": 1, "rho_inf": 1.0}),
    (DYNAMIC / "steel-cantilever-release.json", "cosserat",
     {"release_tip_load": True, "alpha": -0.5, "viscosity_Pa_s": 1000.0, "tip_mass_kg": 0.01}),
    (DYNAMIC / "steel-cantilever-release.json", "fe",
     {"release_tip_load": True, "viscosity_Pa_s": 1000.0, "tip_mass_kg": 0.01}),
    (SCENARIO_DIR / "three-tca-pwm.json", "cosserat", {"steps": 24}),
    (SCENARIO_DIR / "segmented-tca.json", "fe", {"elements": 4}),
]


def flags(options):
    out = []
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        out += [flag] if value is True else [flag, value]
    return out


@pytest.mark.parametrize("path,method,options", CASES,
                         ids=[f"{p.stem}-{m}" for p, m, _ in CASES])
def test_trajectory_equals_the_cli_csv(path, method, options, run_cli, tmp_path):
    out = tmp_path / "trajectory.csv"
    cli = run_cli("simulate", path, "--method", method, "--duration-s", 0.004, "--dt-s", 0.001,
                  *flags(options), "--out", out)
    assert cli.returncode == 0, cli.stderr
    text = out.read_text()
    tr = tcasim.simulate(str(path), method, duration_s=0.004, dt_s=0.001, **options)
    assert tr.completed and tr.status == "converged" and tr.message == ""
    assert tr.to_csv() == text
    written = tmp_path / "python.csv"
    tr.to_csv(written)
    assert written.read_bytes() == out.read_bytes()
    # The arrays hold the file's numbers, up to its digits (at least 9 significant ones;
    # temperatures 9 decimals).
    lines = text.splitlines()
    assert tr.columns == lines[0].split(",")
    assert len(tr) == len(lines) - 1
    for k, line in enumerate(lines[1:]):
        for name, cell in zip(tr.columns, line.split(",")):
            value = tr[name][k]
            if cell == "nan":
                assert math.isnan(value), (name, k)
                continue
            degC = name.endswith("_degC")
            assert float(cell) == pytest.approx(value, rel=6e-9, abs=6e-10 if degC else 0.0), (
                name, k)
    np.testing.assert_array_equal(tr.t_s, tr["t_s"])
    np.testing.assert_array_equal(tr.tip_position_m[:, 2], tr["tip_z_m"])


def test_probe_columns_and_dict_input_round_trip(tmp_path, run_cli):
    d = json.loads((DYNAMIC / "manipulator-voltage-step.json").read_text())
    d["probes"] = [{"name": "mid", "s_m": 0.02, "offset_m": [0.001, 0.0, 0.0]}]
    path = tmp_path / "probe.json"
    path.write_text(json.dumps(d))
    out = tmp_path / "trajectory.csv"
    cli = run_cli("simulate", path, "--duration-s", 0.003, "--dt-s", 0.001, "--out", out)
    assert cli.returncode == 0, cli.stderr
    tr = tcasim.simulate(d, duration_s=0.003, dt_s=0.001)
    assert tr.to_csv() == out.read_text()
    assert tr.columns[-3:] == ["mid_x_m", "mid_y_m", "mid_z_m"]
    assert tr.probes["mid"].shape == (4, 3)
    np.testing.assert_array_equal(tr.probes["mid"][:, 0], tr["mid_x_m"])
    # A Scenario and its dict give the same trajectory.
    sc = tcasim.load_scenario(d)
    assert tcasim.simulate(sc.to_dict(), duration_s=0.003, dt_s=0.001).to_csv() == tr.to_csv()


@pytest.mark.parametrize("method", ["cosserat", "fe"])
def test_failed_step_raises_with_the_partial_trajectory(method, run_cli, tmp_path):
    path = DYNAMIC / "steel-cantilever-release.json"
    out = tmp_path / "trajectory.csv"
    cli = run_cli("simulate", path, "--method", method, "--duration-s", 0.004, "--dt-s", 0.001,
                  "--release-tip-load", "--max-iterations", 1, "--out", out)
    assert cli.returncode == 4
    with pytest.raises(tcasim.SolverError) as e:
        tcasim.simulate(path, method, duration_s=0.004, dt_s=0.001, release_tip_load=True,
                        max_iterations=1)
    tr = e.value.result
    assert isinstance(tr, tcasim.Trajectory)
    assert not tr.completed and tr.status == "max-iterations" and tr.steps_done == 0
    assert "time step to t = 0.001 s failed" in tr.message and tr.message in e.value.message
    assert len(tr) == 1 and tr.t_s[0] == 0.0  # the static state at t = 0 is kept
    assert tr.to_csv() == out.read_text()
    kept = tcasim.simulate(path, method, duration_s=0.004, dt_s=0.001, release_tip_load=True,
                           max_iterations=1, check=False)
    assert kept.to_csv() == tr.to_csv()


@pytest.mark.parametrize("options,key", [
    ({"dt_s": -1.0}, "dt_s"),
    ({"duration_s": 1.0, "dt_s": 1e-9}, "duration_s"),
    ({"alpha": 0.3}, "alpha"),
    ({"output_every": 0}, "output_every"),
    ({"max_iterations": 0}, "max_iterations"),
    ({"viscosity_Pa_s": -1.0}, "viscosity_Pa_s"),
    ({"steps": 100000000}, "steps"),
    ({"elements": 4}, "elements"),  # an option of the other method
    ({"method": "fe", "rho_inf": 2.0}, "rho_inf"),
    ({"method": "fe", "order": 3}, "order"),
    ({"method": "fe", "alpha": -0.1}, "alpha"),
    ({"method": "rk4"}, "method"),
])
def test_an_input_error_names_the_option(options, key):
    kw = {"duration_s": 0.002, "dt_s": 0.001, **options}
    with pytest.raises(tcasim.InputError) as e:
        tcasim.simulate(DYNAMIC / "steel-cantilever-release.json", **kw)
    assert e.value.key == key, str(e.value)
    assert e.value.rule


@pytest.mark.parametrize("method,options,rule", [
    ("cosserat", {"elements": 4}, 'applies to method="fe" only (cosserat: steps, alpha)'),
    ("fe", {"steps": 20}, 'applies to method="cosserat" only (fe: elements, order, rho_inf)'),
])
def test_an_option_of_the_other_method_is_refused_with_the_rule(method, options, rule):
    with pytest.raises(tcasim.InputError) as e:
        tcasim.simulate(DYNAMIC / "steel-cantilever-release.json", method, duration_s=0.002,
                        dt_s=0.001, **options)
    assert e.value.rule == rule, str(e.value)


def test_progress_is_called_and_its_error_propagates():
    calls = []
    tcasim.simulate(DYNAMIC / "steel-cantilever-release.json", duration_s=0.003, dt_s=0.001,
                    progress=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 3), (2, 3), (3, 3)]

    def stop(done, total):
        raise KeyboardInterrupt("stop")

    with pytest.raises(KeyboardInterrupt):
        tcasim.simulate(DYNAMIC / "steel-cantilever-release.json", duration_s=0.003, dt_s=0.001,
                        progress=stop)


def test_the_gil_is_released_while_it_runs():
    """Python code runs in another thread while a simulation is in C++ (as the solve's test in
    test_errors_and_roundtrip.py): with the GIL held, the main thread would stop for the whole
    run; released, its gaps are the operating system's scheduling only."""
    import time

    path = DYNAMIC / "steel-cantilever-release.json"
    kw = {"method": "fe", "dt_s": 1e-3, "elements": 32, "release_tip_load": True}
    t0 = time.perf_counter()
    tcasim.simulate(path, duration_s=0.01, **kw)
    once = time.perf_counter() - t0
    # About 0.3 s of simulation.
    duration_s = min(10.0, max(0.01, round(0.01 * 0.3 / once, 3)))
    longest_gap, run = longest_gap_while(lambda: tcasim.simulate(path, duration_s=duration_s, **kw))
    assert run > 0.1, "the simulation is too short to tell"
    assert longest_gap < 0.5 * run, (longest_gap, run)


def test_adaptive_steps_equal_the_cli_csv_with_dt_s(run_cli, tmp_path):
    """rtol/atol_m/output_every_s are the command's --rtol/--atol-m/--output-every-s: the same
    file, with the dt_s column last and the counts of accepted and rejected steps."""
    path = DYNAMIC / "steel-cantilever-release.json"
    out = tmp_path / "trajectory.csv"
    cli = run_cli("simulate", path, "--method", "fe", "--duration-s", 0.01, "--rtol", 1e-3,
                  "--atol-m", 1e-6, "--output-every-s", 0.005, "--release-tip-load",
                  "--out", out)
    assert cli.returncode == 0, cli.stderr
    assert "time steps accepted" in cli.stderr
    tr = tcasim.simulate(str(path), "fe", duration_s=0.01, rtol=1e-3, atol_m=1e-6,
                         output_every_s=0.005, release_tip_load=True)
    assert tr.to_csv() == out.read_text()
    assert tr.columns[-1] == "dt_s"
    np.testing.assert_allclose(tr.t_s, [0.0, 0.005, 0.01], rtol=0, atol=1e-15)
    assert tr["dt_s"][0] == 0.0 and np.all(tr["dt_s"][1:] > 0.0)
    assert tr.steps_done > 0 and tr.steps_rejected >= 0 and tr.steps_failed == 0


@pytest.mark.parametrize("options,key,rule", [
    ({"dt_s": 0.001, "rtol": 1e-3, "output_every_s": 0.005}, "dt_s", "cannot be given with rtol"),
    ({}, "dt_s", "one of dt_s"),
    ({"rtol": 1e-3}, "output_every_s", "is required with rtol"),
    ({"dt_s": 0.001, "atol_m": 1e-6}, "atol_m", "applies with rtol only"),
])
def test_one_time_step_mode_is_required(options, key, rule):
    with pytest.raises(tcasim.InputError) as e:
        tcasim.simulate(str(DYNAMIC / "steel-cantilever-release.json"), "fe", duration_s=0.01,
                        **options)
    assert e.value.key == key and rule in str(e.value)
