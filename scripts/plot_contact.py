#!/usr/bin/python3
"""Plots the CSVs of validate_contact:
  contact_heavy_rod.png  the heavy rod's finest shapes (both methods, every gap H) over the floor,
                         with the closed-form free span w(x) and its touchdown point l
                         (rod/closed_form.hpp heavy_rod_on_floor); beside it the clamp-moment
                         error against the refinement level (log-log, both methods, against the
                         planar reference and the closed form) with the observed slope;
  contact_onset.png      the onset sweeps: the tip path and the contact force against the load
                         (tip force or TCA temperature), with the closed form of the cantilever
                         on a cylinder.
A missing or empty table (a step that did not run) leaves its panel with a note, so the
script never fails on a partial run.

Usage: /usr/bin/python3 scripts/plot_contact.py OUT_DIR
"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError:
        return []


def num(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return math.nan
    return v


def closed_form_height(B, q, H, x):
    """The clamped heavy rod's free span (rod/closed_form.hpp): w = q l xi^3 / (18 B) - q xi^4 / (24 B)."""
    l = (72.0 * B * H / q) ** 0.25
    if x >= l:
        return 0.0
    xi = l - x
    return q * l * xi ** 3 / (18.0 * B) - q * xi ** 4 / (24.0 * B)


def note(ax, text):
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", fontsize=9, wrap=True)


def plot_heavy_rod(out_dir):
    params = read(f"{out_dir}/heavy_rod_params.csv")
    shapes = read(f"{out_dir}/heavy_rod_shape.csv")
    ladder = read(f"{out_dir}/heavy_rod.csv")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 5))
    if not params:
        note(ax, "no heavy_rod_params.csv (step 1 did not run)")
    penetrating = []
    for i, p in enumerate(params):
        H, B, q, r = num(p["H_m"]), num(p["B_N_m2"]), num(p["q_N_m"]), num(p["radius_m"])
        floor, L = num(p["floor_z_m"]), num(p["length_m"])
        color = f"C{i}"
        xs = [L * k / 400 for k in range(401)]
        # Centerline height = floor + r + w(x) (the lowest surface line at w above the floor).
        ax.plot(xs, [1e3 * (floor + r + closed_form_height(B, q, H, x)) for x in xs], color=color, lw=1,
                label=f"closed form, H = {1e3 * H:.3g} mm")
        l = num(p["closed_free_span_m"])
        ax.plot([l], [1e3 * (floor + r)], marker="v", color=color, ms=9, ls="none")
        ax.axhline(1e3 * floor, color=color, lw=0.8, ls=":")
        for method, style in (("cosserat", "--"), ("fe", ":")):
            pts = [(num(s["x_m"]), num(s["z_m"])) for s in shapes
                   if num(s["H_m"]) == H and s["method"] == method]
            if pts:
                ax.plot([x for x, _ in pts], [1e3 * z for _, z in pts], ls=style, color=color, lw=1.6,
                        label=f"{method} (finest), H = {1e3 * H:.3g} mm")
                # A centerline more than the radius below the floor: the floor was not felt.
                if min(z for _, z in pts) < floor:
                    penetrating.append(f"{method}, H = {1e3 * H:.3g} mm")
    if params:
        floors = [num(p["floor_z_m"]) for p in params]
        h_max = max(num(p["H_m"]) for p in params)
        ax.set_ylim(1e3 * (min(floors) - 0.5 * h_max), 1e3 * 0.5 * h_max)
    if penetrating:
        ax.text(0.02, 0.04, f"{len(penetrating)} solver shapes pass below the floor: contact not solved",
                transform=ax.transAxes, fontsize=8, color="darkred")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("centerline z [mm]")
    ax.set_title("Heavy rod on a floor: shapes; triangles: closed-form touchdown l; dotted: floors")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)

    # Error against refinement: clamp moment against the planar reference (solid) and the
    # closed form (dashed), per method and gap.
    series = defaultdict(list)
    for row in ladder:
        if row.get("converged") != "1" or math.isnan(num(row.get("moment_error_vs_ref"))):
            continue
        key = (row["method"], num(row["H_m"]))
        series[key].append((num(row["level"]), num(row["moment_error_vs_ref"]), num(row["moment_error_vs_closed"])))
    if not series:
        note(ax2, "no converged solves with a base reaction in heavy_rod.csv\n"
                  "(the solvers do not report contact yet?)")
    for i, ((method, H), pts) in enumerate(sorted(series.items())):
        pts.sort()
        levels = [p[0] for p in pts]
        ref = [p[1] if p[1] > 0 else math.nan for p in pts]
        cf = [p[2] if p[2] > 0 else math.nan for p in pts]
        ok = [(a, b) for a, b in zip(levels, ref) if not math.isnan(b)]
        slope = ""
        if len(ok) >= 2:
            slope = f", slope {math.log(ok[-2][1] / ok[-1][1]) / math.log(ok[-1][0] / ok[-2][0]):.2f}"
        line, = ax2.loglog(levels, ref, marker="o", ls="-" if method == "cosserat" else "-.",
                           label=f"{method}, H = {1e3 * H:.3g} mm, vs planar reference{slope}")
        ax2.loglog(levels, cf, marker="x", ls=":", color=line.get_color(), lw=1)
    ax2.set_xlabel("refinement level (shooting steps, FE elements)")
    ax2.set_ylabel("relative clamp-moment error")
    ax2.set_title("Clamp moment error vs refinement (dotted: vs closed form)")
    ax2.grid(True, which="both", alpha=0.3)
    if series:
        ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/contact_heavy_rod.png", dpi=110)
    plt.close(fig)
    print(f"wrote {out_dir}/contact_heavy_rod.png")


def plot_onset(out_dir):
    rows = read(f"{out_dir}/onset_sweep.csv")
    cases = sorted({r["case"] for r in rows})
    fig, axes = plt.subplots(max(len(cases), 1), 2, figsize=(13, 4.5 * max(len(cases), 1)), squeeze=False)
    if not cases:
        note(axes[0][0], "no onset_sweep.csv (step 5 did not run)")
    for (ax_path, ax_force), case in zip(axes, cases):
        mine = [r for r in rows if r["case"] == case]
        finest = max(int(r["points"]) for r in mine)
        for method, style in (("cosserat", "-o"), ("fe", "--s")):
            pts = [r for r in mine if r["method"] == method and int(r["points"]) == finest]
            if not pts:
                continue
            load = [num(r["load"]) for r in pts]
            ok = [r["converged"] == "1" for r in pts]
            ax_path.plot([1e3 * num(r["tip_x_m"]) for r, o in zip(pts, ok) if o],
                         [1e3 * num(r["tip_z_m"]) for r, o in zip(pts, ok) if o], style, ms=3, label=method)
            ax_force.plot([x for x, o in zip(load, ok) if o], [num(r["contact_force_N"]) for r, o in zip(pts, ok) if o],
                          style, ms=3, label=f"{method} contact force")
        closed = [(num(r["load"]), num(r["closed_contact_force_N"])) for r in mine
                  if r["method"] == "cosserat" and int(r["points"]) == finest and not math.isnan(num(r["closed_contact_force_N"]))]
        if closed:
            ax_force.plot([c[0] for c in closed], [c[1] for c in closed], "k:", label="closed form (small slope)")
            onset = num(mine[0]["onset"])
            if not math.isnan(onset):
                ax_force.axvline(onset, color="grey", lw=0.8, ls="--", label="closed-form onset B / (R L)")
        tip_load = mine[0].get("load_kind") == "tip_force_N"
        ax_path.set_title(f"{case}: tip path")
        ax_path.set_xlabel("tip x [mm]")
        ax_path.set_ylabel("tip z [mm]")
        ax_path.grid(True, alpha=0.3)
        ax_path.legend(fontsize=7)
        ax_force.set_title(f"{case}: contact force")
        ax_force.set_xlabel("tip force [N]" if tip_load else "TCA temperature [degC]")
        ax_force.set_ylabel("|contact resultant| [N]")
        ax_force.grid(True, alpha=0.3)
        ax_force.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/contact_onset.png", dpi=110)
    plt.close(fig)
    print(f"wrote {out_dir}/contact_onset.png")


def main(out_dir):
    plot_heavy_rod(out_dir)
    plot_onset(out_dir)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
