#!/usr/bin/python3
"""Plots the CSV files of validate_dynamic_crosscheck:
  dynamic_crosscheck_trajectories.png  tip trajectories of both methods at the finest dt per case,
                                       and their distance over time;
  dynamic_crosscheck_dt.png            max-over-time difference against dt per case, with each
                                       method's own time error (|p(dt) - p(dt/2)|);
  dynamic_crosscheck_h.png             difference against the FE element size (time-extrapolated),
                                       linear and quadratic elements;
  dynamic_crosscheck_energy.png        kinetic and potential energies of both methods over time.
Pass/fail lives in the C++ program (gates.csv); this script only reads and plots.

Usage: /usr/bin/python3 scripts/plot_dynamic_crosscheck.py OUT_DIR
"""
import csv
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def by_case(rows):
    out = OrderedDict()
    for r in rows:
        out.setdefault(r["case"], []).append(r)
    return out


def cases_with_trajectories(out_dir, rows):
    return [c for c in by_case(rows) if os.path.exists(os.path.join(out_dir, f"{c}_trajectory.csv"))]


def grid(n):
    cols = min(n, 4)
    return (n + cols - 1) // cols, cols


def plot_trajectories(out_dir, cases):
    fig, axes = plt.subplots(2, len(cases), figsize=(4.2 * len(cases), 6.4), squeeze=False)
    for k, case in enumerate(cases):
        rows = read(os.path.join(out_dir, f"{case}_trajectory.csv"))
        t = [num(r["t_s"]) for r in rows]
        a, b = axes[0][k], axes[1][k]
        z0 = num(rows[0]["shooting_tip_z_m"])
        for comp, color in (("x", "C0"), ("y", "C1"), ("z", "C2")):
            sh = [1e3 * (num(r[f"shooting_tip_{comp}_m"]) - (z0 if comp == "z" else 0.0)) for r in rows]
            fe = [1e3 * (num(r[f"fe_tip_{comp}_m"]) - (z0 if comp == "z" else 0.0)) for r in rows]
            a.plot(t, sh, color=color, label=f"{comp} shooting" + (" - z(0)" if comp == "z" else ""))
            a.plot(t, fe, color=color, ls="--", label=f"{comp} FE")
        a.set_title(case, fontsize=9)
        a.set_xlabel("t [s]")
        a.set_ylabel("tip displacement [mm]")
        a.grid(alpha=0.3)
        a.legend(fontsize=6)
        d = [max(num(r["fe_diff_m"]), 1e-300) for r in rows]
        b.semilogy(t, d, color="k")
        b.set_xlabel("t [s]")
        b.set_ylabel("|tip FE - tip shooting| [m]")
        b.grid(alpha=0.3, which="both")
    fig.suptitle("Dynamic cross-check: both methods at the finest dt", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "dynamic_crosscheck_trajectories.png"), dpi=110)
    plt.close(fig)


def slope_line(ax, x, y, slope, label):
    if len(x) < 2:
        return
    x0, x1 = min(x), max(x)
    y1 = max(y)
    ax.loglog([x0, x1], [y1 * (x0 / x1) ** slope, y1], ":", color="gray", label=label)


def plot_dt(out_dir, study):
    groups = by_case(study)
    rows_n, cols = grid(len(groups))
    fig, axes = plt.subplots(rows_n, cols, figsize=(4.2 * cols, 3.6 * rows_n), squeeze=False)
    for k, (case, rows) in enumerate(groups.items()):
        ax = axes[k // cols][k % cols]
        dt = [num(r["dt_s"]) for r in rows]
        d = [num(r["difference_over_L"]) for r in rows]
        ax.loglog(dt, d, "o-k", label="|FE - shooting| / L")
        # Each own time error |p(dt) - p(dt/2)| is plotted at the coarser dt of its pair.
        for key, style, label in (("shooting_time_error_over_L", "s--", "shooting |p(dt) - p(dt/2)| / L"),
                                  ("fe_time_error_over_L", "^--", "FE |p(dt) - p(dt/2)| / L")):
            pts = [(dt[i - 1], num(rows[i][key])) for i in range(1, len(rows)) if rows[i][key]]
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], style, label=label)
        slope = 1 if "release" in case else 2
        slope_line(ax, dt, d, slope, f"slope {slope}")
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("dt [s]")
        ax.set_ylabel("max over time / L")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6)
    for k in range(len(groups), rows_n * cols):
        axes[k // cols][k % cols].axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "dynamic_crosscheck_dt.png"), dpi=110)
    plt.close(fig)


def plot_h(out_dir, study):
    groups = by_case(study)
    fig, axes = plt.subplots(1, len(groups), figsize=(4.6 * len(groups), 3.6), squeeze=False)
    for k, (case, rows) in enumerate(groups.items()):
        ax = axes[0][k]
        for order, style, slope in (("1", "o-", 2), ("2", "s-", 4)):
            sel = [r for r in rows if r["fe_order"] == order]
            if not sel:
                continue
            h = [num(r["h_m"]) for r in sel]
            d = [num(r["difference_over_L"]) for r in sel]
            ax.loglog(h, d, style, label=f"{'linear' if order == '1' else 'quadratic'} elements")
            slope_line(ax, h, d, slope, f"slope {slope}")
        ax.set_title(f"{case} (dt {num(rows[0]['dt_s']):g} s, extrapolated)", fontsize=9)
        ax.set_xlabel("element size h [m]")
        ax.set_ylabel("max over time |FE - shooting| / L")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "dynamic_crosscheck_h.png"), dpi=110)
    plt.close(fig)


def plot_energy(out_dir, cases):
    rows_n, cols = grid(len(cases))
    fig, axes = plt.subplots(rows_n, cols, figsize=(4.2 * cols, 3.4 * rows_n), squeeze=False)
    for k, case in enumerate(cases):
        ax = axes[k // cols][k % cols]
        rows = read(os.path.join(out_dir, f"{case}_trajectory.csv"))
        t = [num(r["t_s"]) for r in rows]
        for method, style in (("shooting", "-"), ("fe", "--")):
            name = "FE" if method == "fe" else method
            ax.plot(t, [num(r[f"{method}_kinetic_J"]) for r in rows], "C0" + style, label=f"kinetic ({name})")
            ax.plot(t, [num(r[f"{method}_potential_J"]) for r in rows], "C1" + style, label=f"potential ({name})")
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("energy [J]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    for k in range(len(cases), rows_n * cols):
        axes[k // cols][k % cols].axis("off")
    fig.suptitle("Energies at the finest dt (potential of the loads at t, taken as constant)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "dynamic_crosscheck_energy.png"), dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    out_dir = sys.argv[1]
    dt_rows = read(os.path.join(out_dir, "dynamic_dt_study.csv"))
    h_rows = read(os.path.join(out_dir, "dynamic_h_study.csv"))
    if not dt_rows:
        print(f"plot_dynamic_crosscheck: no dynamic_dt_study.csv rows in {out_dir}", file=sys.stderr)
        return 1
    cases = cases_with_trajectories(out_dir, dt_rows)
    if cases:
        plot_trajectories(out_dir, cases)
        plot_energy(out_dir, cases)
    plot_dt(out_dir, dt_rows)
    if h_rows:
        plot_h(out_dir, h_rows)
    print(f"plot_dynamic_crosscheck: wrote the plots of {len(by_case(dt_rows))} cases to {out_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
