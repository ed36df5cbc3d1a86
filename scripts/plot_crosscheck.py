#!/usr/bin/python3
"""Plots crosscheck.csv (validate_crosscheck, tcasim compare) as crosscheck.png: FE - shooting
position difference (max of tip and mid point) over L against the number of elements, one
panel per FE order, with the 1e-9 L gate line.

Usage: /usr/bin/python3 scripts/plot_crosscheck.py OUT_DIR
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

GATE_OVER_L = 1e-9  # validate_crosscheck's gate (quadratic, finest mesh)


def main(out_dir):
    rows = defaultdict(lambda: ([], []))
    with open(f"{out_dir}/crosscheck.csv", newline="") as f:
        for row in csv.DictReader(f):
            n, d = rows[(int(row["order"]), row["scenario"])]
            tip_over_l = float(row["tip_diff_over_L"])
            length = float(row["tip_diff_m"]) / tip_over_l if tip_over_l > 0 else None
            mid = float(row["mid_diff_m"]) if row["mid_diff_m"] not in ("", "nan") else 0.0
            n.append(int(row["elements"]))
            d.append(max(tip_over_l, mid / length if length else 0.0))
    orders = sorted({k[0] for k in rows}, reverse=True)
    fig, axes = plt.subplots(1, len(orders), figsize=(6.5 * len(orders), 5), squeeze=False)
    for ax, order in zip(axes[0], orders):
        for (o, name), (n, d) in sorted(rows.items()):
            if o == order:
                ax.loglog(n, [x if x > 0 else float("nan") for x in d], marker="o", label=name)
        ax.axhline(GATE_OVER_L, color="k", ls="--", lw=1, label="gate 1e-9 L")
        ax.set_title(f"FE order {order} vs shooting")
        ax.set_xlabel("elements")
        ax.set_ylabel("max(tip, mid) position difference / L")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/crosscheck.png", dpi=120)
    print(f"wrote {out_dir}/crosscheck.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
