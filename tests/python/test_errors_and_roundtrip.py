"""Input errors reach Python as tcasim.InputError with the library's key, value and rule;
a solve that does not converge raises tcasim.SolverError with the partial result; a
scenario round-trips dict -> file -> dict unchanged."""
import copy
import json

import pytest

import tcasim
from conftest import SCENARIO_DIR, longest_gap_while

BASE = SCENARIO_DIR / "circular-manipulator.json"


def base_dict():
    return json.loads(BASE.read_text())


def test_a_temperature_below_absolute_zero_names_key_value_and_rule():
    d = base_dict()
    d["actuators"][0]["drive"]["temperature_degC"] = -400
    with pytest.raises(tcasim.InputError) as e:
        tcasim.solve(d)
    assert e.value.key == "actuators[0].drive.temperature_degC"
    assert e.value.value == "-400"
    assert "absolute zero" in e.value.rule
    assert str(e.value) == f"{e.value.key} = {e.value.value} {e.value.rule}"
    assert isinstance(e.value, ValueError)


def test_an_unknown_key_is_refused_by_path():
    d = base_dict()
    d["body"]["lenght_m"] = 0.04
    with pytest.raises(tcasim.InputError) as e:
        tcasim.load_scenario(d)
    assert (e.value.key, e.value.value) == ("body.lenght_m", "0.04")
    assert e.value.rule.startswith("is not an allowed key here")


def test_python_values_that_are_not_json_are_refused_by_path():
    d = base_dict()
    d["body"]["length_m"] = float("nan")
    with pytest.raises(tcasim.InputError) as e:
        tcasim.load_scenario(d)
    assert e.value.key == "body.length_m" and "finite" in e.value.rule
    d["body"]["length_m"] = {1, 2}
    with pytest.raises(tcasim.InputError) as e:
        tcasim.load_scenario(d)
    assert e.value.key == "body.length_m" and "set" in e.value.rule


def test_the_cli_and_python_give_the_same_message(run_cli, tmp_path):
    d = base_dict()
    d["actuators"][0]["count"] = 1000000000
    p = tmp_path / "bad.json"
    p.write_text(json.dumps(d))
    cli = run_cli("solve", p)
    assert cli.returncode == 2
    with pytest.raises(tcasim.InputError) as e:
        tcasim.solve(d)
    assert cli.stderr == f"tcasim: input error: {e.value}\n"


@pytest.mark.parametrize("kwargs,key,value", [
    ({"steps": 3}, "steps", "3"),
    ({"scheme": "rk5"}, "scheme", "rk5"),
    ({"rtol": 2.0}, "rtol", "2"),
    ({"rtol": 1e-6, "steps": 10}, "rtol", "1e-06"),
    ({"method": "fe", "order": 3}, "order", "3"),
    ({"method": "fe", "elements": 0}, "elements", "0"),
    ({"method": "fe", "linear_solver": "lapack"}, "linear_solver", "lapack"),
    ({"method": "bem"}, "method", "bem"),
])
def test_bad_options_name_the_keyword(kwargs, key, value):
    with pytest.raises(tcasim.InputError) as e:
        tcasim.solve(BASE, **kwargs)
    assert (e.value.key, e.value.value) == (key, value)


def test_a_missing_file_is_an_input_error():
    with pytest.raises(tcasim.InputError) as e:
        tcasim.load_scenario(SCENARIO_DIR / "no-such-file.json")
    assert "cannot be opened" in e.value.rule


def test_sweep_and_inverse_name_their_arguments():
    with pytest.raises(tcasim.InputError) as e:
        tcasim.sweep(BASE, "nope", temperatures_degC=[30])
    assert e.value.key == "actuator" and e.value.value == "nope"
    with pytest.raises(tcasim.InputError) as e:
        tcasim.sweep(BASE, "tca", tensions_N=[1.0])
    assert e.value.key == "tensions_N"
    with pytest.raises(tcasim.InputError) as e:
        tcasim.inverse(BASE, [0, 0, 0.04], actuators=["tca", "tca"])
    assert e.value.key == "actuators"
    with pytest.raises(tcasim.InputError) as e:
        tcasim.grasp(BASE, mass_g=10, friction=0.5, fingers=2)
    assert e.value.key == "tip_constraint.normal"


def test_a_solve_that_does_not_converge_raises_with_the_partial_result():
    # A steel rod's tendon pulled with 1 MN (the rod would curl many times over): the load
    # steps of a single linear element fail.
    d = json.loads((SCENARIO_DIR / "steel-4-tendon.json").read_text())
    d["actuators"][0]["drive"]["tension_N"] = 1e6
    with pytest.raises(tcasim.SolverError) as e:
        tcasim.solve(d, method="fe", elements=1, order=1)
    r = e.value.result
    assert isinstance(r, tcasim.Result) and not r.converged
    assert r.message and r.message in str(e.value)
    # check=False returns the same partial result.
    r2 = tcasim.solve(d, method="fe", elements=1, order=1, check=False)
    assert not r2.converged and r2.status == r.status
    assert r2.to_dict()["message"] == r2.message


def test_dict_file_dict_round_trip(tmp_path):
    for path in sorted(SCENARIO_DIR.glob("*.json")):
        d = json.loads(path.read_text())
        if d["schema"] != "tcasim.scenario/1":
            continue
        sc = tcasim.load_scenario(copy.deepcopy(d))
        assert sc.to_dict() == d
        out = tmp_path / path.name
        sc.save(out)
        back = tcasim.load_scenario(out)
        assert back.to_dict() == d and back.path == str(out)
        assert back.to_json() == sc.to_json() == out.read_text()
        # Both give the same result.
        a = tcasim.solve(sc, check=False).to_dict()
        b = tcasim.solve(back, check=False).to_dict()
        a.pop("wall_time_s"), b.pop("wall_time_s")
        assert a == b


def test_edited_dicts_are_validated_again():
    sc = tcasim.load_scenario(BASE)
    d = sc.to_dict()
    d["actuators"][0]["drive"]["temperature_degC"] = 120
    hot = tcasim.solve(d)
    cold = tcasim.solve(sc)
    assert sc.to_dict()["actuators"][0]["drive"]["temperature_degC"] != 120  # a copy
    assert hot.tip_position_m[0] != cold.tip_position_m[0]
    d["actuators"][0]["drive"]["temperature_degC"] = "hot"
    with pytest.raises(tcasim.InputError) as e:
        tcasim.solve(d)
    assert e.value.key == "actuators[0].drive.temperature_degC"


def test_the_gil_is_released_during_solves():
    """Python code runs in another thread while a solve is in C++: with the GIL held, the
    main thread would stop for the whole solve (one gap between its ticks as long as the
    solve); released, its gaps are the operating system's scheduling only."""
    import time

    sc = tcasim.load_scenario(BASE)
    # An FE solve long enough to tell (about 0.3 s; FE time grows with the elements).
    t0 = time.perf_counter()
    tcasim.solve(sc, method="fe", elements=GIL_TEST_ELEMENTS)
    once = time.perf_counter() - t0
    elements = min(10000, max(GIL_TEST_ELEMENTS, int(GIL_TEST_ELEMENTS * 0.3 / once)))
    longest_gap, duration = longest_gap_while(
        lambda: tcasim.solve(sc, method="fe", elements=elements))
    assert duration > 0.1, "the solve is too short to tell"
    assert longest_gap < 0.5 * duration, (longest_gap, duration)


# Elements of the first FE solve of the GIL test (scaled up to a solve of about 0.3 s).
GIL_TEST_ELEMENTS = 400


def test_a_missing_umfpack_plugin_names_the_keyword_and_the_path(tmp_path):
    # A fresh interpreter: the plugin is loaded once per process, and this one may hold it.
    import os
    import subprocess
    import sys
    code = ("import tcasim, sys\n"
            "try:\n"
            f"    tcasim.solve({str(BASE)!r}, method='fe', linear_solver='umfpack')\n"
            "except tcasim.InputError as e:\n"
            "    print(e.key); print(e.value); print(e.rule); sys.exit(0)\n"
            "sys.exit('no InputError')\n")
    env = dict(os.environ, TCASIM_PLUGIN_DIR=str(tmp_path))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    key, value, rule = out.stdout.splitlines()[:3]
    assert (key, value) == ("linear_solver", "umfpack")
    assert f"{tmp_path}/libtcasim_umfpack.so: cannot open shared object file" in rule
    assert "TCASIM_PLUGIN_DIR" in rule
