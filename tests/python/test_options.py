"""Every option is checked once, for both front ends (study/options.hpp): a value the user
gave is never taken for "not given" (steps=0 and rtol=0 are refused, not the defaults), a
Python integer or float that does not fit is a tcasim.InputError naming the keyword (not
pybind11's TypeError), and the command line and Python give the same rule and value."""
import math

import pytest

import tcasim
from conftest import SCENARIO_DIR, SOURCE_DIR

BASE = SCENARIO_DIR / "circular-manipulator.json"
CANTILEVER = SOURCE_DIR / "tests" / "cli" / "steel-cantilever.json"
FINGER = SCENARIO_DIR / "gripper-finger.json"
TIME = {"duration_s": 0.002, "dt_s": 0.001}


def refusal(call):
    with pytest.raises(tcasim.InputError) as e:
        call()
    return e.value


@pytest.mark.parametrize("kwargs,key,value,rule", [
    ({"steps": 0}, "steps", "0", "must be an even number in [2, 100000]"),
    ({"steps": 10**12}, "steps", "1000000000000", "must be an even number in [2, 100000]"),
    ({"steps": -2}, "steps", "-2", "must be an even number in [2, 100000]"),
    ({"steps": 10**30}, "steps", str(10**30), "must be an integer in [-9223372036854775808, "
                                             "9223372036854775807] (64 bits)"),
    ({"steps": 40.0}, "steps", "40.0", "must be an integer"),
    ({"steps": True}, "steps", "True", "must be an integer"),
    ({"steps": "40"}, "steps", "'40'", "must be an integer"),
    ({"rtol": 0}, "rtol", "0", "must be in (0, 1)"),
    ({"rtol": 0.0}, "rtol", "0", "must be in (0, 1)"),
    ({"rtol": float("nan")}, "rtol", "nan", "must be in (0, 1)"),
    ({"rtol": 10**400}, "rtol", str(10**400),
     "must be a number within the range of a double (|x| < 1.8e308)"),
    ({"rtol": "1e-6"}, "rtol", "'1e-6'", "must be a number"),
    ({"method": "fe", "elements": 0}, "elements", "0", "must be an integer in [1, 10000]"),
    ({"method": "fe", "elements": 10**12}, "elements", "1000000000000",
     "must be an integer in [1, 10000]"),
    ({"method": "fe", "order": 0}, "order", "0", "must be 1 or 2"),
])
def test_solve_refuses_by_rule_naming_the_keyword(kwargs, key, value, rule):
    e = refusal(lambda: tcasim.solve(BASE, **kwargs))
    assert (e.key, e.value, e.rule) == (key, value, rule)


@pytest.mark.parametrize("kwargs,key", [
    ({"steps": 0}, "steps"),
    ({"rtol": 0}, "rtol"),
    ({"jobs": 10**12}, "jobs"),
    ({"jobs": 0}, "jobs"),
    ({"chunk": 0}, "chunk"),
    ({"chunk": 10**30}, "chunk"),
    ({"temperatures_degC": [30, 10**400]}, "temperatures_degC"),
    ({"temperatures_degC": [30, float("nan")]}, "temperatures_degC"),
    ({"temperatures_degC": "30"}, "temperatures_degC"),
    ({"method": "fe", "elements": 10**12}, "elements"),
])
def test_sweep_refuses_by_rule_naming_the_keyword(kwargs, key):
    kw = {"temperatures_degC": [30, 40], **kwargs}
    assert refusal(lambda: tcasim.sweep(BASE, "tca", **kw)).key == key


@pytest.mark.parametrize("kwargs,key", [
    ({"steps": 0}, "steps"),
    ({"steps": 10**12}, "steps"),
    ({"duration_s": float("nan")}, "duration_s"),
    ({"dt_s": 10**400}, "dt_s"),
    ({"output_every": 10**20}, "output_every"),
    ({"max_iterations": 10**12}, "max_iterations"),
    ({"tip_mass_kg": float("inf")}, "tip_mass_kg"),
    ({"alpha": float("nan")}, "alpha"),
    ({"method": "fe", "elements": 0}, "elements"),
    ({"method": "fe", "elements": 10**12}, "elements"),
    ({"method": "fe", "rho_inf": float("nan")}, "rho_inf"),
])
def test_simulate_refuses_by_rule_naming_the_keyword(kwargs, key):
    kw = {**TIME, **kwargs}
    assert refusal(lambda: tcasim.simulate(CANTILEVER, **kw)).key == key


def test_inverse_grasp_and_tca_curve_refuse_by_rule_naming_the_keyword():
    assert refusal(lambda: tcasim.inverse(BASE, [0, 0, math.nan])).key == "target_m"
    assert refusal(lambda: tcasim.inverse(BASE, [0, 0])).key == "target_m"
    e = refusal(lambda: tcasim.inverse(BASE, [0, 0, 0.04], max_temperature_degC=10**400))
    assert e.key == "max_temperature_degC"
    e = refusal(lambda: tcasim.grasp(FINGER, mass_g=10, friction=0.5, fingers=10**12))
    assert (e.key, e.value) == ("fingers", "1000000000000")
    assert refusal(lambda: tcasim.grasp(FINGER, mass_g=math.inf, friction=0.5,
                                        fingers=2)).key == "mass_g"
    assert refusal(lambda: tcasim.tca_curve(BASE, [30], tension_N=10**400)).key == "tension_N"
    assert refusal(lambda: tcasim.tca_curve(BASE, [10**400], tension_N=1)).key == \
        "temperatures_degC"


def test_numpy_integers_and_python_ints_as_floats_are_taken():
    np = pytest.importorskip("numpy")
    a = tcasim.solve(BASE, steps=np.int64(40), rtol=None)
    b = tcasim.solve(BASE, steps=40)
    assert list(a.tip_position_m) == list(b.tip_position_m)
    c = tcasim.solve(BASE, rtol=np.float64(1e-6))
    assert c.converged


# (python keywords, command-line flags) that must be refused with the same rule and value.
SAME_REFUSAL = [
    ("solve", {"steps": 0}, ["solve", BASE, "--steps", "0"]),
    ("solve", {"rtol": 0}, ["solve", BASE, "--rtol", "0"]),
    ("solve", {"steps": 10**12}, ["solve", BASE, "--steps", "1000000000000"]),
    ("solve", {"method": "bem"}, ["solve", BASE, "--method", "bem"]),
    ("solve", {"method": "fe", "elements": 0}, ["solve", BASE, "--method", "fe",
                                                "--elements", "0"]),
    ("sweep", {"steps": 0}, ["sweep", BASE, "--actuator", "tca", "--temperatures-degC", "30:40:10",
                             "--steps", "0"]),
    ("sweep", {"chunk": 0}, ["sweep", BASE, "--actuator", "tca", "--temperatures-degC", "30:40:10",
                             "--chunk", "0"]),
    ("simulate", {"steps": 0}, ["simulate", CANTILEVER, "--duration-s", "0.002", "--dt-s", "0.001",
                                "--steps", "0", "--out", "-"]),
]


@pytest.mark.parametrize("function,kwargs,argv", SAME_REFUSAL)
def test_the_cli_and_python_refuse_with_the_same_rule(run_cli, function, kwargs, argv):
    if function == "solve":
        e = refusal(lambda: tcasim.solve(BASE, **kwargs))
    elif function == "sweep":
        e = refusal(lambda: tcasim.sweep(BASE, "tca", temperatures_degC=[30, 40], **kwargs))
    else:
        e = refusal(lambda: tcasim.simulate(CANTILEVER, **TIME, **kwargs))
    cli = run_cli(*argv)
    assert cli.returncode == 2, cli.stderr
    flag = "--" + e.key.replace("_", "-")
    assert cli.stderr == f"tcasim: input error: {flag} = {e.value} {e.rule}\n"
