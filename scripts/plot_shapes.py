#!/usr/bin/python3
"""Plots the suite shapes written by validate_shapes: one 3D figure per scenario.

Usage: /usr/bin/python3 scripts/plot_shapes.py OUT_DIR
Reads OUT_DIR/<name>_shape.csv (curve,actuator_id,s_m,x_m,y_m,z_m) and, when present,
OUT_DIR/shapes_summary.csv (base frame, status); writes OUT_DIR/<name>_shape.png with the
centerline thick, the actuator paths thin, equal axis scaling and the base frame marked.
Columns are read by name; pass/fail lives in validate_shapes.
"""
import csv
import sys
from collections import OrderedDict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MM = 1e3  # plots are in millimetres


def read_curves(path):
    """Curves of one shape CSV, in file order: name -> (actuator_id, points [n x 3] in m)."""
    curves = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            entry = curves.setdefault(row["curve"], (int(row["actuator_id"]), []))
            entry[1].append((float(row["x_m"]), float(row["y_m"]), float(row["z_m"])))
    return OrderedDict((k, (a, np.array(p))) for k, (a, p) in curves.items())


def read_summary(out_dir):
    path = out_dir / "shapes_summary.csv"
    if not path.exists():
        return {}
    with open(path, newline="") as f:
        return {row["scenario"]: row for row in csv.DictReader(f)}


def set_equal_axes(ax, points):
    """Equal scaling on the three axes: a cube around the points' bounding box."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre = 0.5 * (lo + hi)
    half = 0.5 * max(float((hi - lo).max()), 1e-9)
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    return 2.0 * half


def plot_one(name, curves, summary_row, png):
    fig = plt.figure(figsize=(5.6, 5.2))
    ax = fig.add_subplot(projection="3d")
    all_points = np.vstack([p for _, p in curves.values()]) * MM
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, (curve, (actuator_id, p)) in enumerate(curves.items()):
        p = p * MM
        if actuator_id < 0:
            ax.plot(p[:, 0], p[:, 1], p[:, 2], color="black", linewidth=3.0, label=curve)
            ax.scatter(*p[-1], color="black", s=18, marker="o")
        else:
            ax.plot(p[:, 0], p[:, 1], p[:, 2], color=colors[k % len(colors)], linewidth=1.0, label=curve)
    extent = set_equal_axes(ax, all_points)
    if summary_row and summary_row.get("base_x_m"):
        base = np.array([float(summary_row[f"base_{c}_m"]) for c in "xyz"]) * MM
        length = 0.2 * extent
        for axis, color in zip(("e1", "e2", "e3"), ("tab:red", "tab:green", "tab:blue")):
            d = np.array([float(summary_row[f"base_{axis}_{c}"]) for c in "xyz"])
            # A line from the base along the axis, labelled at its end (3D arrow heads read ambiguously).
            end = base + length * d
            ax.plot(*zip(base, end), color=color, linewidth=2.0)
            ax.text(*(base + 1.15 * length * d), axis, color=color, fontsize=8, fontweight="bold")
        ax.scatter(*base, color="tab:red", s=30, marker="s", label="base (clamp)")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    title = name
    if summary_row:
        title += f"\n{summary_row['status']}, tip = ({', '.join(f'{MM * float(summary_row[k]):.2f}' for k in ('tip_x_m', 'tip_y_m', 'tip_z_m'))}) mm"
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)
    print(f"wrote {png}")


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    out_dir = Path(argv[1])
    summary = read_summary(out_dir)
    files = sorted(out_dir.glob("*_shape.csv"))
    if not files:
        print(f"plot_shapes: no *_shape.csv in {out_dir}")
        return 1
    for path in files:
        name = path.name[: -len("_shape.csv")]
        plot_one(name, read_curves(path), summary.get(name), out_dir / f"{name}_shape.png")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
