#!/usr/bin/python3
"""Plot the measured-TCA comparison written by validate_measured_tca.

Usage: /usr/bin/python3 scripts/plot_measured_tca.py OUT_DIR [OUT/measured_tca.png]
Left: force against strain, measured points and the nominal models (measured fiber diameter
and the paper's d0) at each temperature. Middle: the same with the fitted shear modulus and
expansion. Right: the fitted values with their standard errors beside the published ranges.
Reads columns by name; pass/fail lives in validate_measured_tca.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    out = Path(argv[1])
    png = Path(argv[2]) if len(argv) > 2 else out / "measured_tca.png"
    points = read(out / "measured_tca_points.csv")
    curves = read(out / "measured_tca_curves.csv")
    fits = read(out / "measured_tca_fit.csv")
    temps = sorted({float(r["temperature_degC"]) for r in points})
    colors = {t: c for t, c in zip(temps, ["tab:blue", "tab:red", "tab:green", "tab:purple"])}
    styles = {"measured": "-", "paper-d0": "--"}
    labels = {"measured": "measured d0", "paper-d0": "paper d0 = 2DL/l"}

    fig = plt.figure(figsize=(16, 5.2))
    grid = fig.add_gridspec(2, 3, width_ratios=[1.0, 1.0, 0.75])
    ax_nominal = fig.add_subplot(grid[:, 0])
    ax_fitted = fig.add_subplot(grid[:, 1], sharey=ax_nominal)
    for ax, which in ((ax_nominal, "nominal"), (ax_fitted, "fitted")):
        for t in temps:
            sel = [r for r in points if float(r["temperature_degC"]) == t]
            ax.plot([float(r["strain"]) for r in sel], [float(r["measured_tension_N"]) for r in sel],
                    "o", color=colors[t], label=f"measured, {t:g} degC")
            for tca in ("measured", "paper-d0"):
                c = [r for r in curves if r["tca"] == tca and r["parameters"] == which
                     and float(r["temperature_degC"]) == t]
                ax.plot([float(r["strain"]) for r in c], [float(r["tension_N"]) for r in c],
                        styles[tca], color=colors[t], label=f"model, {labels[tca]}, {t:g} degC")
        ax.set_xlabel("strain (delta / L)")
        ax.set_title(f"{which} material parameters")
        ax.grid(alpha=0.3)
    ax_nominal.set_ylabel("force [N]")
    ax_nominal.set_ylim(-1.0, 8.0)
    ax_nominal.legend(fontsize=7, loc="upper left")

    for row, (param, scale, unit) in enumerate((("shear_modulus", 1e-9, "GPa"),
                                                ("expansion", 1e3, "1e-3 1/K"))):
        ax = fig.add_subplot(grid[row, 2])
        sel = [r for r in fits if r["parameter"] == param]
        if sel:
            lo, hi = float(sel[0]["published_lo"]) * scale, float(sel[0]["published_hi"]) * scale
            ax.axvspan(lo, hi, color="0.85", label="published range")
        for k, r in enumerate(sel):
            v = float(r["value"]) * scale
            e = float(r["standard_error"]) * scale if r["standard_error"] not in ("", "nan") else 0.0
            ax.errorbar([v], [k], xerr=[e], fmt="o", capsize=4, color="k" if r["tca"] == "measured" else "0.5")
            ax.annotate(f"{labels.get(r['tca'], r['tca'])}: {v:.3g} +- {e:.1g}", (v, k),
                        textcoords="offset points", xytext=(6, 6), fontsize=7)
        ax.set_yticks([])
        ax.set_ylim(-0.8, len(sel) - 0.2)
        ax.set_xlabel(f"fitted {param} [{unit}]")
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle("Nylon 6,6 monocoil contraction TCA, isometric tests: model against measurement")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
