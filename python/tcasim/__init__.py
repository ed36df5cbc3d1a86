"""tcasim: kinetostatics of soft rod robots actuated by twisted-and-coiled actuators (TCAs).

The Python face of the tcasim C++ library and command line (docs/python.md): the same
scenario files, the same solvers, the same numbers as ``tcasim solve``.

    import tcasim
    sc = tcasim.load_scenario("validation/scenarios/circular-manipulator.json")
    r = tcasim.solve(sc, method="cosserat")          # or method="fe", elements=32, ...
    r.tip_position_m, r.centerline_position_m         # numpy arrays [m], world frame
    d = sc.to_dict(); d["actuators"][0]["drive"]["temperature_degC"] = 120
    r2 = tcasim.solve(d)                              # a dict is validated like a file
    sw = tcasim.sweep(sc, "tca", temperatures_degC=range(25, 151, 5))

Units are SI unless a name carries a suffix (_degC, _deg, _g). Bad input raises
tcasim.InputError (.key, .value, .rule); a solve that does not converge raises
tcasim.SolverError carrying the partial result (or returns it with check=False).
The design-study runner on Dask is tcasim.study (imported on demand).
"""

from ._errors import DomainError, InputError, SolverError
from ._tcasim import (
    Result,
    Scenario,
    data_directory,
    grasp,
    inverse,
    load_scenario,
    solve,
    sweep,
    tca_curve,
)

__all__ = [
    "DomainError",
    "InputError",
    "Result",
    "Scenario",
    "SolverError",
    "data_directory",
    "grasp",
    "inverse",
    "load_scenario",
    "solve",
    "sweep",
    "tca_curve",
]
__version__ = "0.1.0"
