"""Inverse kinetostatics: the TCA temperature that puts the manipulator's tip at a target
point, checked by a forward solve at that temperature.

  PYTHONPATH=build/python /usr/bin/python3 examples/python/inverse_target.py
"""
import argparse
import pathlib

import numpy as np

import tcasim

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenario", default=ROOT / "validation/scenarios/circular-manipulator.json")
    ap.add_argument("--target-temperature-degC", type=float, default=100.0,
                    help="the target is the tip of a forward solve at this temperature")
    args = ap.parse_args()

    sc = tcasim.load_scenario(args.scenario)
    d = sc.to_dict()
    d["actuators"][0]["drive"]["temperature_degC"] = args.target_temperature_degC
    target = tcasim.solve(d).tip_position_m
    print(f"target tip position: {target} m")

    inv = tcasim.inverse(sc, target)
    t = inv["actuators"][0]["temperature_degC"]
    print(f"inverse: {inv['status']} after {inv['iterations']} steps, temperature {t:.9f} degC, "
          f"distance {inv['distance_m']:.2e} m")

    d["actuators"][0]["drive"]["temperature_degC"] = t
    check = tcasim.solve(d)
    err = np.linalg.norm(check.tip_position_m - target)
    print(f"forward check at {t:.9f} degC: |tip - target| = {err:.2e} m")
    if err > 1e-8:
        raise SystemExit("the forward check misses the target")


if __name__ == "__main__":
    main()
