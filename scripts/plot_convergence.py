#!/usr/bin/python3
"""Plots convergence.csv (validate_convergence, tcasim converge) as convergence.png:
log-log FE error against element length h, one panel per FE order, one line per scenario
(solid: against the shooting reference; dotted: against the FE's Richardson extrapolation),
with reference slopes 2 and 4.

Usage: /usr/bin/python3 scripts/plot_convergence.py OUT_DIR
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out_dir):
    studies = defaultdict(lambda: ([], [], []))
    with open(f"{out_dir}/convergence.csv", newline="") as f:
        for row in csv.DictReader(f):
            h, e, r = studies[(int(row["order"]), row["scenario"])]
            h.append(float(row["h_m"]))
            e.append(float(row["error_m"]))
            r.append(float(row["richardson_error_m"]))
    orders = sorted({k[0] for k in studies})
    fig, axes = plt.subplots(1, len(orders), figsize=(6.5 * len(orders), 5), squeeze=False)
    for ax, order in zip(axes[0], orders):
        h_all = []
        for (o, name), (h, e, r) in sorted(studies.items()):
            if o != order:
                continue
            line, = ax.loglog(h, e, marker="o", label=name)
            ax.loglog(h, [x if x > 0 else float("nan") for x in r], ls=":", color=line.get_color())
            h_all += h
        # Reference slopes over the coarsest decade, through the median error.
        h_hi = max(h_all)
        h_lo = max(min(h_all), h_hi / 10)
        e_mid = sorted(e for (o, _), (_, es, _) in studies.items() if o == order for e in es)
        e0 = e_mid[len(e_mid) // 2]
        for slope, style in ((2, "k--"), (4, "k-.")):
            ax.loglog([h_lo, h_hi], [e0 * (h_lo / h_hi) ** slope, e0], style, lw=1, label=f"slope {slope}")
        ax.set_title(f"FE order {order}: tip error vs h (solid: vs shooting, dotted: vs Richardson)")
        ax.set_xlabel("element length h [m]")
        ax.set_ylabel("position error [m]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/convergence.png", dpi=120)
    print(f"wrote {out_dir}/convergence.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
