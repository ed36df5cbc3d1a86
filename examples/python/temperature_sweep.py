"""Temperature sweep of the paper's circular manipulator with both solvers, and the TCA's own
elongation curve, plotted to a PNG (headless).

  PYTHONPATH=build/python /usr/bin/python3 examples/python/temperature_sweep.py [--out DIR]
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tcasim  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenario", default=ROOT / "validation/scenarios/circular-manipulator.json")
    ap.add_argument("--out", default="out/python-examples", help="output folder")
    ap.add_argument("--step-degC", type=float, default=5.0, help="temperature step [degC]")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    sc = tcasim.load_scenario(args.scenario)
    actuator = sc.actuators[0]
    temps = np.arange(25.0, 150.0 + 1e-9, args.step_degC)
    sweeps = {m: tcasim.sweep(sc, actuator, temperatures_degC=temps, method=m)
              for m in ("cosserat", "fe")}
    curve = tcasim.tca_curve(sc, temps, tension_N=0.0)

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for method, sw in sweeps.items():
        ax1.plot(sw["temperature_degC"], 1e3 * sw["tip_x_m"], "o-" if method == "fe" else "-",
                 label=f"tip x ({method})", markersize=3)
    ax1.set_xlabel("TCA temperature [degC]")
    ax1.set_ylabel("tip deflection x [mm]")
    ax1.set_title(f"{sc.name}: tip deflection")
    ax1.legend()
    ax2.plot(temps, 1e3 * curve["elongation_m"], label="free TCA, F = 0")
    ax2.plot(temps, 1e3 * sweeps["cosserat"][f"{actuator}_elongation_m"], label="TCA in the rod")
    ax2.set_xlabel("TCA temperature [degC]")
    ax2.set_ylabel("TCA elongation [mm]")
    ax2.set_title("TCA elongation")
    ax2.legend()
    fig.tight_layout()
    png = out / "temperature_sweep.png"
    fig.savefig(png, dpi=100)
    worst = np.max(np.abs(sweeps["cosserat"]["tip_x_m"] - sweeps["fe"]["tip_x_m"]))
    print(f"{len(temps)} temperatures, all converged: "
          f"{all(all(sw['converged']) for sw in sweeps.values())}; "
          f"largest |tip x| difference cosserat - fe: {worst:.3e} m; plot: {png}")


if __name__ == "__main__":
    main()
