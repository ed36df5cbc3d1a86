#!/usr/bin/python3
"""Times `tcasim sweep` with --jobs 1 and --jobs N on one long sweep and prints the medians
and the speed-up (the speed target: --jobs 2 at least 1.8x faster on 2 cores for 1000
points). The runs alternate (1, N, 1, N, ...) so a load change on a shared machine hits both;
every CSV must equal the first --jobs 1 CSV byte for byte.

With --machine, every repeat also runs N independent --jobs 1 processes at once, each held to
a CPU of its own: their throughput against one process alone is what the machine gives N
copies of this code (less than N when its cores slow each other down, e.g. on a virtual
machine whose cores share the host's), the reference for the --jobs N speed-up.

Usage: /usr/bin/python3 bench/sweep_jobs.py --tcasim build/bin/tcasim [--jobs 2] [--repeats 7]
       [--points 1000] [--method cosserat|fe] [--scenario FILE --actuator NAME --start 25 --stop 150]
       [--machine] [-- extra sweep flags]
Standard library only.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def children_cpu():
    """User + system CPU seconds of the finished child processes."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tcasim", required=True)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--repeats", type=int, default=7)
    p.add_argument("--points", type=int, default=1000)
    p.add_argument("--method", default="cosserat")
    p.add_argument("--scenario", default=str(ROOT / "validation" / "scenarios" / "circular-manipulator.json"))
    p.add_argument("--actuator", default="tca")
    p.add_argument("--start", type=float, default=25.0)
    p.add_argument("--stop", type=float, default=150.0)
    p.add_argument("--machine", action="store_true",
                   help="also time N independent --jobs 1 processes at once, one per CPU")
    a = p.parse_args(argv)
    cpus = sorted(os.sched_getaffinity(0))
    if a.machine and len(cpus) < a.jobs:
        print(f"sweep_jobs: --machine needs {a.jobs} CPUs, this process may use {len(cpus)}", file=sys.stderr)
        return 2
    if a.machine and a.repeats < 2:
        print("sweep_jobs: --machine needs --repeats 2 or more (the first repeat makes the reference CSV)",
              file=sys.stderr)
        return 2
    step = (a.stop - a.start) / (a.points - 1)
    sweep = [a.tcasim, "sweep", a.scenario, "--actuator", a.actuator, "--method", a.method,
             "--temperatures-degC", f"{a.start}:{a.stop}:{step!r}"] + extra
    times = {1: [], a.jobs: []}
    cpu = {1: [], a.jobs: []}
    together = []  # --machine: wall time of the N processes at once
    reference = None
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.repeats):
            if a.machine and reference is not None:
                outs = [Path(tmp) / f"m{i}.csv" for i in range(a.jobs)]
                t0 = time.perf_counter()
                procs = [subprocess.Popen(sweep + ["--jobs", "1", "--out", str(o)], stdout=subprocess.DEVNULL,
                                          stderr=subprocess.PIPE, text=True,
                                          preexec_fn=lambda c=cpus[i]: os.sched_setaffinity(0, {c}))
                         for i, o in enumerate(outs)]
                errors = [proc.communicate()[1] for proc in procs]
                together.append(time.perf_counter() - t0)
                for proc, err, o in zip(procs, errors, outs):
                    if proc.returncode != 0 or o.read_text() != reference:
                        print(f"sweep_jobs: an independent --jobs 1 process (repeat {r}) failed or wrote a "
                              f"different CSV: {err[-500:]}", file=sys.stderr)
                        return 1
            for jobs in (1, a.jobs):
                out = Path(tmp) / f"j{jobs}.csv"
                t0, c0 = time.perf_counter(), children_cpu()
                proc = subprocess.run(sweep + ["--jobs", str(jobs), "--out", str(out)], capture_output=True, text=True)
                times[jobs].append(time.perf_counter() - t0)
                cpu[jobs].append(children_cpu() - c0)
                if proc.returncode != 0:
                    print(f"sweep_jobs: exit code {proc.returncode}: {proc.stderr[-500:]}", file=sys.stderr)
                    return 1
                text = out.read_text()
                if reference is None:
                    reference = text
                    rows = text.count("\n") - 1
                elif text != reference:
                    print(f"sweep_jobs: --jobs {jobs} (repeat {r}) wrote a different CSV", file=sys.stderr)
                    return 1
    m1, mn = statistics.median(times[1]), statistics.median(times[a.jobs])
    print(f"sweep_jobs: {rows} points, {a.method}, {a.repeats} repeats, {os.cpu_count()} cores "
          f"(load average {os.getloadavg()[0]:.2f} at the end)")
    print(f"  --jobs 1: median {m1:.3f} s (min {min(times[1]):.3f}, max {max(times[1]):.3f})")
    print(f"  --jobs {a.jobs}: median {mn:.3f} s (min {min(times[a.jobs]):.3f}, max {max(times[a.jobs]):.3f})")
    print(f"  speed-up of the medians: {m1 / mn:.2f}x; CSVs identical")
    c1, cn = statistics.median(cpu[1]), statistics.median(cpu[a.jobs])
    print(f"  CPU time (user + system) medians: {c1:.3f} s with --jobs 1, {cn:.3f} s with --jobs {a.jobs} "
          f"(the parallel run's extra work: {100 * (cn / c1 - 1):+.1f} %)")
    print(f"  wall / CPU with --jobs {a.jobs}: {mn / cn:.2f} (1 / {a.jobs} = {1 / a.jobs:.2f} when every thread "
          "has a core of its own; a busy machine shows more)")
    if together:
        mt = statistics.median(together)
        machine = a.jobs * m1 / mt
        print(f"  {a.jobs} independent --jobs 1 processes at once, one per CPU: median {mt:.3f} s, so this machine "
              f"gives {a.jobs} copies {machine:.2f}x the throughput of one; --jobs {a.jobs} reaches "
              f"{100 * (m1 / mn) / machine:.0f} % of that")
    return 0


if __name__ == "__main__":
    sys.exit(main())
