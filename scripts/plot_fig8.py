#!/usr/bin/python3
"""Plots fig8_force.csv (validate_fig8_force) as fig8.png: held-tip force vs temperature.

Usage: /usr/bin/python3 scripts/plot_fig8.py OUT_DIR
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out_dir):
    wire = defaultdict(lambda: ([], []))
    pinned = defaultdict(lambda: ([], []))
    with open(f"{out_dir}/fig8_force.csv", newline="") as f:
        for row in csv.DictReader(f):
            t = float(row["temperature_degC"])
            wire[row["material"]][0].append(t)
            wire[row["material"]][1].append(1e3 * float(row["force_N"]))
            pinned[row["material"]][0].append(t)
            pinned[row["material"]][1].append(1e3 * float(row["pinned_force_N"]))
    fig, ax = plt.subplots(figsize=(6.5, 4.0))
    for material, (t, fo) in sorted(wire.items()):
        ax.plot(t, fo, marker=".", label=f"{material}: wire tension")
    for material, (t, fo) in sorted(pinned.items()):
        ax.plot(t, fo, linestyle="--", alpha=0.6, label=f"{material}: |pinned reaction|")
    ax.set_title("26 mm body, tip held where the free tip is at 55 degC (Fig. 8)")
    ax.set_xlabel("TCA temperature [degC]")
    ax.set_ylabel("tip force [mN]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/fig8.png", dpi=120)
    print(f"wrote {out_dir}/fig8.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
