"""What a solve costs through Python beyond the same solve in C++ (issue target: <= 10 us).

Runs bench_solve_api (Google Benchmark: cosserat::solve / beam_fe::solve of the shipped
circular manipulator from a loaded model) and times tcasim.solve(scenario) of the same
loaded scenario with timeit, then prints both medians and their difference.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--build build] [--repeats 15]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import time
import timeit

import tcasim

ROOT = pathlib.Path(__file__).resolve().parents[1]


def cpp_medians(binary, repeats):
    p = subprocess.run([str(binary), f"--benchmark_repetitions={repeats}",
                        "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                       capture_output=True, text=True, check=True)
    out = {}
    for b in json.loads(p.stdout)["benchmarks"]:
        if b.get("aggregate_name") == "median":
            scale = {"us": 1e-6, "ns": 1e-9, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
            out[b["run_name"]] = b["real_time"] * scale
    return out


def py_median(fn, repeats):
    number = max(1, int(0.2 / max(1e-6, min(timeit.repeat(fn, number=1, repeat=3)))))
    times = timeit.repeat(fn, number=number, repeat=repeats)
    return statistics.median(t / number for t in times)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=ROOT / "build")
    ap.add_argument("--repeats", type=int, default=15)
    args = ap.parse_args()
    sc = tcasim.load_scenario(ROOT / "validation/scenarios/circular-manipulator.json")
    doc = sc.to_dict()
    cpp = cpp_medians(pathlib.Path(args.build) / "bench" / "bench_solve_api", args.repeats)
    rows = [
        ("cosserat", cpp["BM_SolveCosserat"], py_median(lambda: tcasim.solve(sc), args.repeats)),
        ("fe", cpp["BM_SolveFe"], py_median(lambda: tcasim.solve(sc, "fe"), args.repeats)),
    ]
    print("Separate programs (bench_solve_api, then timeit; a busy machine moves both):")
    print(f"{'solve':10} {'C++ median':>12} {'Python median':>14} {'difference':>11}")
    for name, c, p in rows:
        print(f"{name:10} {c * 1e6:10.1f} us {p * 1e6:12.1f} us {(p - c) * 1e6:8.1f} us")
    # Paired, in one process: rounds alternating the solve looped in C++ (the same library
    # code, _solve_times_cpp) and tcasim.solve from Python; the median of the per-round
    # differences cancels the drift of a shared machine.
    print("Paired in one process (median over rounds of median C++ vs median Python solve):")
    for method in ("cosserat", "fe"):
        n = 20 if method == "cosserat" else 5
        diffs, cs, ps, c_all, p_all = [], [], [], [], []
        for _ in range(args.repeats):
            c_times = tcasim._tcasim._solve_times_cpp(sc, method, n)
            times = []
            for _ in range(n):
                t0 = time.perf_counter()
                tcasim.solve(sc, method)
                times.append(time.perf_counter() - t0)
            c, p = statistics.median(c_times), statistics.median(times)
            cs.append(c), ps.append(p), diffs.append(p - c)
            c_all += c_times
            p_all += times
        print(f"{method:10} {statistics.median(cs) * 1e6:10.1f} us {statistics.median(ps) * 1e6:12.1f} us "
              f"{statistics.median(diffs) * 1e6:8.1f} us   (fastest call: C++ {min(c_all) * 1e6:.1f} us, "
              f"Python {min(p_all) * 1e6:.1f} us, difference {(min(p_all) - min(c_all)) * 1e6:.1f} us)")
    # What else a Python caller may pay: a dict (parsed and validated per call) and reading
    # the numpy fields of a result.
    r = tcasim.solve(sc)
    t_dict = py_median(lambda: tcasim.solve(doc), args.repeats) - rows[0][2]
    t_fields = py_median(lambda: (r.tip_position_m, r.centerline_position_m, r.actuators), args.repeats)
    print(f"solve(dict) instead of solve(Scenario): +{t_dict * 1e6:.1f} us (parsing and validation)")
    print(f"reading tip_position_m, centerline_position_m, actuators: {t_fields * 1e6:.2f} us")


if __name__ == "__main__":
    main()
