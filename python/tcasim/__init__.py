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
    tr = tcasim.simulate(sc, duration_s=0.1, dt_s=1e-3)  # as `tcasim simulate`
    tr.t_s, tr["tip_x_m"], tr.to_csv("trajectory.csv")

Units are SI unless a name carries a suffix (_degC, _deg, _g). Bad input raises
tcasim.InputError (.key, .value, .rule); a solve that does not converge raises
tcasim.SolverError carrying the partial result (or returns it with check=False).
The design-study runner on Dask is tcasim.study (imported on demand).
"""

import os as _os
import pathlib as _pathlib


def _find_installed_data():
    """An installed package (<prefix>/lib/python3.X/dist-packages/tcasim) uses the data
    installed with it (<prefix>/share/tcasim), wherever the prefix was moved, unless
    TCASIM_DATA_DIR is set (docs/python.md)."""
    if _os.environ.get("TCASIM_DATA_DIR"):
        return
    here = _pathlib.Path(__file__).resolve().parent
    for prefix in list(here.parents)[:5]:
        data = prefix / "share" / "tcasim"
        if (data / "materials").is_dir() and (prefix / "lib").is_dir():
            _os.environ["TCASIM_DATA_DIR"] = str(data)
            return


def _find_installed_plugins():
    """Likewise the UMFPACK plugin installed with the package (<prefix>/lib/tcasim), unless
    TCASIM_PLUGIN_DIR is set: the extension module, under lib/python3.X, is not where the
    library looks for it by itself (docs/python.md)."""
    if _os.environ.get("TCASIM_PLUGIN_DIR"):
        return
    here = _pathlib.Path(__file__).resolve().parent
    for prefix in list(here.parents)[:5]:
        plugins = prefix / "lib" / "tcasim"
        if (plugins / "libtcasim_umfpack.so").is_file() and (prefix / "share" / "tcasim").is_dir():
            _os.environ["TCASIM_PLUGIN_DIR"] = str(plugins)
            return


_find_installed_data()
_find_installed_plugins()

from ._errors import DomainError, InputError, SolverError  # noqa: E402
from ._tcasim import (  # noqa: E402
    Result,
    Scenario,
    Trajectory,
    data_directory,
    grasp,
    inverse,
    load_scenario,
    simulate,
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
    "Trajectory",
    "data_directory",
    "grasp",
    "inverse",
    "load_scenario",
    "simulate",
    "solve",
    "sweep",
    "tca_curve",
]
__version__ = "0.1.0"
