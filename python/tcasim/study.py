"""Design studies on Dask distributed: parameter grids or lists of scenarios, one solve per
point, every result (and every failure, with its message) gathered into one CSV table.

    from tcasim import study
    rows = study.run_study(
        "validation/scenarios/square-manipulator.json",
        grid={"actuators[u-tca].routing.offset_m[0]": [0.002, 0.003],
              "actuators[u-tca].drive.temperature_degC": [60, 90, 120],
              "tip_mass_g": [0, 1, 2]},
        setters={"tip_mass_g": study.tip_mass_g},
        out="study.csv")

Inputs are key paths into the scenario document (docs/python.md "Design studies"):
dots between keys, ``[i]`` for list elements, ``[name]`` for the element of a list of
objects whose "name" is name (``actuators[u-tca]``); a missing object on the way is created
(``tip_load.force_N[2]`` on a scenario without a tip load). An input called ``method``
chooses the solver per point. ``setters`` maps other input names to functions
``f(document, value)`` that edit the document (e.g. tip_mass_g below).

By default the study runs on a LocalCluster of this machine; ``address`` (or a
``client``) sends it to a running scheduler, e.g. one started by dask-jobqueue on a Slurm
cluster (docs/python.md). Progress is printed to stderr.
"""

import copy
import csv
import itertools
import math
import re
import sys
import time

__all__ = ["grid", "run_study", "set_path", "tip_mass_g", "write_csv", "solve_point"]

STANDARD_GRAVITY_M_S2 = 9.80665  # common/units.hpp kStandardGravity_m_s2

_TOKEN = re.compile(r"([^.\[\]]+)|\[([^\]]*)\]")


def grid(**axes):
    """The Cartesian product of named value lists, as a list of dicts (last axis fastest):
    grid(a=[1, 2], b=[3, 4]) -> [{a: 1, b: 3}, {a: 1, b: 4}, {a: 2, b: 3}, {a: 2, b: 4}]."""
    names = list(axes)
    return [dict(zip(names, combo)) for combo in itertools.product(*(list(axes[n]) for n in names))]


def _tokens(path):
    out = []
    pos = 0
    for m in _TOKEN.finditer(path):
        if m.start() != pos and path[pos:m.start()] != ".":
            raise ValueError(f"bad key path {path!r}")
        pos = m.end()
        out.append(("key", m.group(1)) if m.group(1) is not None else ("index", m.group(2)))
    if pos != len(path) or not out:
        raise ValueError(f"bad key path {path!r}")
    return out


def set_path(document, path, value):
    """Sets ``document[path] = value`` for a key path (see the module help); returns the
    document. Raises tcasim.InputError naming the path when it does not fit the document."""
    from . import InputError

    tokens = _tokens(path)
    node = document
    for i, (kind, name) in enumerate(tokens):
        last = i == len(tokens) - 1
        nxt = None if last else tokens[i + 1][0]
        if kind == "key":
            if not isinstance(node, dict):
                raise InputError(path, repr(value), f"cannot set key {name!r}: not an object there")
            if last:
                node[name] = value
            else:
                if name not in node:
                    node[name] = {} if nxt == "key" else [0.0, 0.0, 0.0]
                node = node[name]
        else:
            if not isinstance(node, list):
                raise InputError(path, repr(value), f"cannot index [{name}]: not a list there")
            if re.fullmatch(r"-?\d+", name):
                k = int(name)
                if not -len(node) <= k < len(node):
                    raise InputError(path, repr(value), f"index [{k}] is outside the list of {len(node)}")
            else:
                matches = [j for j, e in enumerate(node) if isinstance(e, dict) and e.get("name") == name]
                if len(matches) != 1:
                    raise InputError(path, repr(value), f"[{name}] names no single element of the list")
                k = matches[0]
            if last:
                node[k] = value
            else:
                node = node[k]
    return document


def tip_mass_g(document, mass_g):
    """Setter: a tip mass [g] hanging under gravity, tip_load.force_N = (0, 0, -m g) (world -z)."""
    load = document.setdefault("tip_load", {"force_N": [0.0, 0.0, 0.0], "moment_Nm": [0.0, 0.0, 0.0]})
    load["force_N"] = [0.0, 0.0, -float(mass_g) * 1e-3 * STANDARD_GRAVITY_M_S2]
    return document


def _number(v):
    if v is None:
        return None
    return float(v)


def _outputs(result):
    """The output columns of one solve (the result file's headline numbers)."""
    tip = result.tip_position_m
    row = {
        "scenario": result.scenario,
        "method": result.method,
        "converged": bool(result.converged),
        "status": result.status,
        "iterations": int(result.iterations),
        "residual": _number(result.residual),
        "tip_x_m": float(tip[0]),
        "tip_y_m": float(tip[1]),
        "tip_z_m": float(tip[2]),
        "bending_radius_m": _number(result.bending_radius_m),
    }
    reaction = result.tip_reaction_force_N
    if reaction is not None:
        row.update({f"tip_reaction_{c}_N": float(v) for c, v in zip("xyz", reaction)})
    for a in result.actuators:
        row[f"{a['name']}_tension_N"] = float(a["tension_N"])
        row[f"{a['name']}_elongation_m"] = float(a["elongation_m"])
        if "coils_closed" in a:
            row[f"{a['name']}_coils_closed"] = bool(a["coils_closed"])
    row["wall_time_s"] = float(result.wall_time_s)
    row["message"] = result.message
    return row


def solve_point(base, inputs, setters=None, method="cosserat", options=None):
    """Solves one point: `base` (a scenario dict, or a path or dict for a scenario list) with
    `inputs` applied; returns its row (inputs, outputs, and `error` = "" or the failure:
    "<ErrorType>: <message>"). Never raises for a failed point."""
    import tcasim

    setters = setters or {}
    options = dict(options or {})
    row = dict(inputs)
    try:
        if isinstance(base, dict):
            doc = copy.deepcopy(base)
        else:
            doc = tcasim.load_scenario(base).to_dict()
        point_method = method
        for name, value in inputs.items():
            if name == "method":
                point_method = value
            elif name == "scenario_file":
                continue
            elif name in setters:
                setters[name](doc, value)
            else:
                set_path(doc, name, value)
        result = tcasim.solve(doc, method=point_method, check=False, **options)
        row.update(_outputs(result))
        row["error"] = "" if result.converged else f"SolverError: {result.status}: {result.message}"
    except Exception as e:  # every failure is recorded in its row
        row.update({"converged": False, "status": "error"})
        row["error"] = f"{type(e).__name__}: {e}"
    return row


def _solve_batch(base, batch, setters, method, options):
    return [(index, solve_point(base if b is None else b, inputs, setters, method, options))
            for index, b, inputs in batch]


class _Progress:
    """Progress on stderr: in place on a terminal, whole lines (every 10 %) in a log."""

    def __init__(self, total, stream=None, enabled=True):
        self.total, self.enabled = total, enabled
        self.stream = sys.stderr if stream is None else stream
        self.done = self.failed = 0
        self.start = time.monotonic()
        self.tty = enabled and hasattr(stream, "isatty") and stream.isatty()
        self.next_line = 0

    def update(self, rows):
        self.done += len(rows)
        self.failed += sum(1 for r in rows if r.get("error"))
        if not self.enabled:
            return
        elapsed = time.monotonic() - self.start
        text = f"tcasim study: {self.done}/{self.total} points, {self.failed} failed, {elapsed:.1f} s"
        if self.tty:
            self.stream.write("\r" + text + ("\n" if self.done == self.total else ""))
            self.stream.flush()
        elif self.done >= self.next_line or self.done == self.total:
            self.stream.write(text + "\n")
            self.stream.flush()
            self.next_line = self.done + max(1, self.total // 10)


def write_csv(rows, path):
    """Writes rows (dicts) as one CSV table: the columns in order of first appearance, a
    missing value as an empty cell, booleans as 1/0, floats in shortest round-trip form."""
    columns = []
    for r in rows:
        for k in r:
            if k not in columns:
                columns.append(k)

    def cell(v):
        if v is None or (isinstance(v, float) and math.isnan(v)):
            return ""
        if isinstance(v, bool):
            return int(v)
        if isinstance(v, (list, tuple, dict)):
            return repr(v)
        return v

    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([cell(r.get(c)) for c in columns])
    return columns


def run_study(base=None, grid=None, *, points=None, scenarios=None, setters=None,
              method="cosserat", options=None, out=None, client=None, address=None,
              n_workers=None, threads_per_worker=1, processes=True, batch_size=None,
              progress=True):
    """Runs a design study on Dask distributed and returns its rows (one dict per point, in
    point order); with `out`, also writes them as one CSV table.

    base: the scenario the inputs edit (tcasim.Scenario, dict or path).
    grid: {input: values}: every combination (tcasim.study.grid), or
    points: a list of {input: value} dicts; inputs are key paths, "method", or setters' names.
    scenarios: instead of base: a list of scenarios (paths or dicts), one point each (column
        "scenario_file"); grid/points then apply to each of them.
    method: "cosserat" or "fe"; options: solve options ({"elements": 32}, see tcasim.solve).
    client: a dask.distributed Client; address: a scheduler address ("tcp://host:8786");
        neither: a LocalCluster with n_workers (default: one per core), threads_per_worker,
        processes (False: threads in this process; the solves release the GIL).
    batch_size: points per task (default: about 4 tasks per worker thread).
    Each row: the inputs, then scenario, method, converged, status, iterations, residual,
    tip_x_m, tip_y_m, tip_z_m [m], bending_radius_m [m], per actuator <name>_tension_N [N],
    <name>_elongation_m [m] (<name>_coils_closed), wall_time_s, message, and error ("" or
    the failure "<ErrorType>: <message>": a failed point keeps its row).
    """
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError as e:  # pragma: no cover
        raise ImportError("tcasim.study needs Dask distributed (Debian: python3-distributed)") from e
    import tcasim

    if points is not None and grid is not None:
        raise ValueError("give grid or points, not both")
    point_list = points if points is not None else globals()["grid"](**grid) if grid else [{}]
    tasks = []  # (index, scenario or None for base, inputs)
    if scenarios is not None:
        if base is not None:
            raise ValueError("give base or scenarios, not both")
        for s in scenarios:
            doc = tcasim.load_scenario(s).to_dict() if not isinstance(s, dict) else s
            label = str(s) if not isinstance(s, dict) else doc.get("name", "")
            for p in point_list:
                tasks.append((len(tasks), doc, {"scenario_file": label, **p}))
        base_doc = None
    else:
        if base is None:
            raise ValueError("give base or scenarios")
        base_doc = tcasim.load_scenario(base).to_dict()
        tasks = [(i, None, dict(p)) for i, p in enumerate(point_list)]

    own_cluster = None
    own_client = None
    if client is None:
        if address is not None:
            client = own_client = Client(address)
        else:
            own_cluster = LocalCluster(n_workers=n_workers, threads_per_worker=threads_per_worker,
                                       processes=processes, dashboard_address=None)
            client = own_client = Client(own_cluster)
    try:
        threads = max(1, sum(client.nthreads().values()))
        size = batch_size or max(1, math.ceil(len(tasks) / (4 * threads)))
        batches = [tasks[i:i + size] for i in range(0, len(tasks), size)]
        base_future = client.scatter(base_doc, broadcast=True) if base_doc is not None else None
        futures = [client.submit(_solve_batch, base_future, b, setters, method, options, pure=False)
                   for b in batches]
        bar = _Progress(len(tasks), enabled=progress)
        rows = [None] * len(tasks)
        for future in as_completed(futures):
            try:
                done = future.result()
            except Exception as e:  # a lost worker: the batch's points are failed rows
                batch = batches[futures.index(future)]
                done = [(i, {**inputs, "converged": False, "status": "error",
                             "error": f"{type(e).__name__}: {e}"}) for i, _, inputs in batch]
            for index, row in done:
                rows[index] = row
            bar.update([r for _, r in done])
    finally:
        if own_client is not None:
            own_client.close()
        if own_cluster is not None:
            own_cluster.close()
    if out is not None:
        write_csv(rows, out)
    return rows
