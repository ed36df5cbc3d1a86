"""Voltage step of the circular manipulator's electro-thermal TCA (0 -> 0.714 V at t = 0+):
the TCA temperature, its tension and the tip over time by rod dynamics (tcasim.simulate, the
numbers of `tcasim simulate`), plotted to a PNG (headless), the trajectory CSV beside it.

  PYTHONPATH=build/python /usr/bin/python3 examples/python/voltage_step.py [--out DIR]
      [--duration-s T] [--dt-s DT] [--method cosserat|fe]
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import tcasim  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenario",
                    default=ROOT / "validation/scenarios/dynamic/manipulator-voltage-step.json")
    ap.add_argument("--out", default="out/python-examples", help="output folder")
    ap.add_argument("--duration-s", type=float, default=10.0,
                    help="simulated time [s] (default: 3 thermal time constants)")
    ap.add_argument("--dt-s", type=float, default=0.05, help="time step [s]")
    ap.add_argument("--method", default="cosserat", choices=["cosserat", "fe"])
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    sc = tcasim.load_scenario(args.scenario)
    tca = sc.actuators[0]
    tr = tcasim.simulate(sc, args.method, duration_s=args.duration_s, dt_s=args.dt_s)
    csv = out / "voltage_step.csv"
    tr.to_csv(csv)

    t = tr.t_s
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(13, 4))
    ax1.plot(t, tr[f"{tca}_temperature_degC"])
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("TCA temperature [degC]")
    ax1.set_title(f"{sc.name}: temperature")
    ax2.plot(t, 1e3 * tr[f"{tca}_tension_N"])
    ax2.set_xlabel("t [s]")
    ax2.set_ylabel("TCA tension [mN]")
    ax2.set_title("tension")
    for axis in "xz":
        ax3.plot(t, 1e3 * tr[f"tip_{axis}_m"], label=f"tip {axis}")
    ax3.set_xlabel("t [s]")
    ax3.set_ylabel("tip position [mm]")
    ax3.set_title(f"tip ({args.method})")
    ax3.legend()
    fig.tight_layout()
    png = out / "voltage_step.png"
    fig.savefig(png, dpi=100)
    T = tr[f"{tca}_temperature_degC"]
    print(f"{len(tr)} rows to t = {t[-1]:.3g} s, {tr.status}; temperature {T[0]:.2f} -> "
          f"{T[-1]:.2f} degC, tip x {1e3 * tr['tip_x_m'][0]:.3f} -> "
          f"{1e3 * tr['tip_x_m'][-1]:.3f} mm; plot: {png}, trajectory: {csv}")


if __name__ == "__main__":
    main()
