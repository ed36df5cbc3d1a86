"""A design study on Dask: TCA offset x temperature x tip mass for the square manipulator (straight body: the offset needs no other change),
every point one solve, all rows in one CSV (inputs, outputs, failures with their message).

  PYTHONPATH=build/python /usr/bin/python3 examples/python/design_study.py [--out study.csv]
      [--address tcp://scheduler:8786] [--workers N] [--threads]

Without --address the study runs on a LocalCluster of this machine (--threads: worker
threads in this process, which start faster; the solves release the GIL).
"""
import argparse
import pathlib

import numpy as np

from tcasim import study

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenario", default=ROOT / "validation/scenarios/square-manipulator.json")
    ap.add_argument("--out", default="out/python-examples/design_study.csv")
    ap.add_argument("--address", help="scheduler address (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--threads", action="store_true", help="LocalCluster of threads")
    ap.add_argument("--points", type=int, default=4, help="values per axis")
    args = ap.parse_args()
    pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)

    grid = {
        "actuators[u-tca].routing.offset_m[0]": [float(v) for v in np.linspace(0.001, 0.003, args.points)],
        "actuators[u-tca].drive.temperature_degC": [float(v) for v in np.linspace(40.0, 150.0, args.points)],
        "tip_mass_g": [float(v) for v in np.linspace(0.0, 2.0, args.points)],
    }
    rows = study.run_study(args.scenario, grid, setters={"tip_mass_g": study.tip_mass_g},
                           out=args.out, address=args.address, n_workers=args.workers,
                           processes=not args.threads)
    failed = [r for r in rows if r["error"]]
    best = max((r for r in rows if not r["error"]), key=lambda r: abs(r["tip_x_m"]))
    print(f"{len(rows)} points, {len(failed)} failed; CSV: {args.out}")
    print("largest tip deflection: {:.3f} mm at offset {:.4f} m, {:.1f} degC, {:.2f} g".format(
        1e3 * abs(best["tip_x_m"]), best["actuators[u-tca].routing.offset_m[0]"],
        best["actuators[u-tca].drive.temperature_degC"], best["tip_mass_g"]))


if __name__ == "__main__":
    main()
