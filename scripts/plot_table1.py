#!/usr/bin/python3
"""Plots table1_grasp.csv (validate_table1_grasp) as table1.png: grasp temperature vs mass.

Usage: /usr/bin/python3 scripts/plot_table1.py OUT_DIR
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out_dir):
    sets = defaultdict(lambda: ([], []))
    measured, paper = {}, {}
    with open(f"{out_dir}/table1_grasp.csv", newline="") as f:
        for row in csv.DictReader(f):
            m = float(row["mass_g"])
            key = (row["material"], row["f12_form"], row["calibration"])
            sets[key][0].append(m)
            sets[key][1].append(float(row["temperature_degC"]))
            measured[m] = float(row["measured_degC"])
            paper[m] = float(row["paper_degC"])
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ms = sorted(measured)
    ax.plot(ms, [measured[m] for m in ms], "ks", label="measured firm grip (Table I)")
    ax.plot(ms, [paper[m] for m in ms], "k^", mfc="none", label="paper model (Table I)")
    for (material, f12, cal), (m, t) in sorted(sets.items()):
        style = "-" if cal == "none" else ":"
        label = f"{material}, f12 {f12}" + ("" if cal == "none" else f", {cal}")
        ax.plot(m, t, style, marker=".", label=label)
    ax.set_xlabel("grasped mass [g]")
    ax.set_ylabel("grasp temperature [degC]")
    ax.set_xticks(ms)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/table1.png", dpi=120)
    print(f"wrote {out_dir}/table1.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
