#!/usr/bin/python3
"""Plots fig6_radius.csv (validate_fig6_radius) as fig6.png: bending radius vs temperature.

Usage: /usr/bin/python3 scripts/plot_fig6.py OUT_DIR
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out_dir):
    curves = defaultdict(lambda: ([], []))
    with open(f"{out_dir}/fig6_radius.csv", newline="") as f:
        for row in csv.DictReader(f):
            if row["bending_radius_m"] == "":
                continue
            t, r = curves[(row["manipulator"], row["material"])]
            t.append(float(row["temperature_degC"]))
            r.append(1e3 * float(row["bending_radius_m"]))
    manipulators = sorted({k[0] for k in curves})
    fig, axes = plt.subplots(len(manipulators), 1, figsize=(6.5, 3.2 * len(manipulators)), squeeze=False)
    for ax, name in zip(axes[:, 0], manipulators):
        for (m, material), (t, r) in sorted(curves.items()):
            if m == name:
                ax.plot(t, r, marker=".", label=material)
        ax.set_title(f"{name}: three-point inner-edge radius (Fig. 6)")
        ax.set_xlabel("TCA temperature [degC]")
        ax.set_ylabel("bending radius [mm]")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(f"{out_dir}/fig6.png", dpi=120)
    print(f"wrote {out_dir}/fig6.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
