#!/usr/bin/python3
"""Plots the CSV files of validate_dynamics: dynamics_release.png (released cantilever: tip
trajectory and energies), dynamics_energy.png (pulse-forced rod: energy, work, dissipation and
the balance residual), dynamics_orders.png (errors against dt and the quasi-static gaps against
the drive rate, with the observed orders), dynamics_voltage_step.png (full run) and
dynamics_pwm.png (PWM-driven three-TCA rod: temperatures against the closed form, the tip
against the static tip at the instantaneous temperatures, the tip path across the axis) and
dynamics_adaptive.png (step 9, full run or --adaptive-only: per case the max tip error against
rtol, and against wall time for adaptive and fixed steps, both methods).

Usage: /usr/bin/python3 scripts/plot_dynamics.py OUT_DIR
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def column(rows, key):
    return [float(r[key]) for r in rows]


def plot_release(out_dir):
    rows = read(f"{out_dir}/release.csv")
    t = column(rows, "t_s")
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.6))
    a.plot(t, [1e3 * v for v in column(rows, "tip_x_m")], label="tip x")
    a.plot(t, [1e3 * (v - 0.5) for v in column(rows, "tip_z_m")], label="tip z - L")
    a.set_xlabel("t [s]")
    a.set_ylabel("tip displacement [mm]")
    a.set_title("Released steel cantilever: tip")
    a.grid(alpha=0.3)
    a.legend()
    for key, label in (("kinetic_J", "kinetic"), ("potential_J", "potential"), ("total_J", "total")):
        b.plot(t, [1e3 * v for v in column(rows, key)], label=label)
    b.set_xlabel("t [s]")
    b.set_ylabel("energy [mJ]")
    b.set_title("Released steel cantilever: energies")
    b.grid(alpha=0.3)
    b.legend()
    fig.tight_layout()
    fig.savefig(f"{out_dir}/dynamics_release.png", dpi=110)
    plt.close(fig)


def plot_energy(out_dir):
    rows = read(f"{out_dir}/energy.csv")
    cases = defaultdict(list)
    for r in rows:
        cases[r["case"]].append(r)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
    for ax, name in zip(axes, ("undamped", "damped")):
        rs = cases.get(name, [])
        if not rs:
            continue
        t = column(rs, "t_s")
        for key, label in (("energy_J", "E (kinetic + strain)"), ("work_J", "work in W"),
                           ("dissipated_J", "dissipated D"), ("balance_J", "E - E0 + D - W")):
            ax.plot(t, [1e6 * v for v in column(rs, key)], label=label)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("energy [uJ]")
        ax.set_title(f"sin^2 tip-force pulse, {name}, dt 1 ms")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/dynamics_energy.png", dpi=110)
    plt.close(fig)


def plot_orders(out_dir):
    studies = defaultdict(list)
    # Panel a: orders in dt; panel b: quasi-static gaps against the drive rate.
    panel_of = {"dt_order.csv": "a", "quasi_static_order.csv": "b", "heated_ramp_order.csv": "b",
                "pwm_quasi_static_order.csv": "b"}
    for name, panel in panel_of.items():
        path = f"{out_dir}/{name}"
        if os.path.exists(path):
            for r in read(path):
                studies[(panel, r["study"])].append(r)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (panel, study), rs in studies.items():
        h, e = column(rs, "h"), column(rs, "error")
        orders = [r["observed_order"] for r in rs if r["observed_order"]]
        label = f"{study} [{', '.join(f'{float(o):.2f}' for o in orders)}]"
        ax = b if panel == "b" else a
        ax.loglog(h, e, marker="o", label=label)
    a.set_xlabel("dt [s]")
    a.set_ylabel("error (relative)")
    a.set_title("Order in dt (observed orders in brackets)")
    b.set_xlabel("drive rate: 1 / tau [1/s] (ramps), 1 / slow-down (PWM)")
    b.set_ylabel("largest gap (/ L; PWM: / tip travel)")
    b.set_title("Quasi-static limit")
    for ax in (a, b):
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/dynamics_orders.png", dpi=110)
    plt.close(fig)


def plot_voltage_step(out_dir):
    """Voltage step on the circular manipulator (full run only; skipped when absent)."""
    path = f"{out_dir}/voltage_step.csv"
    if not os.path.exists(path):
        return False
    rows = read(path)
    t = column(rows, "t_s")
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.6))
    a.plot(t, column(rows, "temperature_degC"), label="TCA temperature (dynamics)")
    a.plot(t, column(rows, "closed_form_temperature_degC"), "--", label="closed-form step response")
    a.set_xlabel("t [s]")
    a.set_ylabel("temperature [degC]")
    a.set_title("Voltage step: TCA temperature")
    a.grid(alpha=0.3)
    a.legend()
    for key, skey, label in (("tip_x_m", "static_tip_x_m", "x"), ("tip_z_m", "static_tip_z_m", "z")):
        line, = b.plot(t, [1e3 * v for v in column(rows, key)], label=f"tip {label}")
        b.plot(t, [1e3 * v for v in column(rows, skey)], ":", color=line.get_color(),
               label=f"static at the steady temperature ({label})")
    b.set_xlabel("t [s]")
    b.set_ylabel("tip position [mm]")
    b.set_title("Voltage step: tip of the manipulator")
    b.grid(alpha=0.3)
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/dynamics_voltage_step.png", dpi=110)
    plt.close(fig)
    return True


def plot_pwm(out_dir):
    """PWM-driven three-TCA rod (the run at the scenario's own rate, slow = 1)."""
    path = f"{out_dir}/pwm.csv"
    if not os.path.exists(path):
        return False
    rows = [r for r in read(path) if float(r["slow"]) == 1.0]
    t = column(rows, "t_s")
    names = [k[: -len("_closed_form_degC")] for k in rows[0] if k.endswith("_closed_form_degC")]
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(13, 3.8))
    for name in names:
        line, = a.plot(t, column(rows, f"{name}_temperature_degC"), label=f"{name} (dynamics)")
        a.plot(t, column(rows, f"{name}_closed_form_degC"), "k:", lw=1)
    a.plot([], [], "k:", lw=1, label="closed form (piecewise exponential)")
    a.set_xlabel("t [s]")
    a.set_ylabel("temperature [degC]")
    a.set_title("PWM voltages: TCA temperatures")
    a.legend(fontsize=7)
    for key, label in (("x", "x"), ("y", "y"), ("z", "z")):
        line, = b.plot(t, [1e3 * v for v in column(rows, f"tip_{key}_m")], label=f"tip {label}")
        b.plot(t, [1e3 * v for v in column(rows, f"static_tip_{key}_m")], ":", color=line.get_color(),
               label=f"static at the instantaneous temperatures ({label})")
    b.set_xlabel("t [s]")
    b.set_ylabel("tip position [mm]")
    b.set_title("Tip against the quasi-static tip")
    b.legend(fontsize=6)
    c.plot([1e3 * v for v in column(rows, "tip_x_m")], [1e3 * v for v in column(rows, "tip_y_m")],
           label="dynamics")
    c.plot([1e3 * v for v in column(rows, "static_tip_x_m")], [1e3 * v for v in column(rows, "static_tip_y_m")],
           ":", label="quasi-static")
    c.set_xlabel("tip x [mm]")
    c.set_ylabel("tip y [mm]")
    c.set_title("Tip path across the axis (out of plane)")
    c.set_aspect("equal", adjustable="datalim")
    c.legend(fontsize=7)
    for ax in (a, b, c):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/dynamics_pwm.png", dpi=110)
    plt.close(fig)
    return True


def plot_adaptive(out_dir):
    path = f"{out_dir}/adaptive.csv"
    if not os.path.exists(path):
        return False
    rows = read(path)
    cases = list(dict.fromkeys(r["case"] for r in rows))
    fig, axes = plt.subplots(2, len(cases), figsize=(4.2 * len(cases), 7), squeeze=False)
    styles = {"cosserat": ("C0", "shooting"), "fe": ("C1", "FE")}
    for k, case in enumerate(cases):
        a, b = axes[0][k], axes[1][k]
        for method, (color, label) in styles.items():
            sel = [r for r in rows if r["case"] == case and r["method"] == method]
            ad = [r for r in sel if r["kind"] == "adaptive"]
            fx = [r for r in sel if r["kind"] == "fixed"]
            if ad:
                a.loglog(column(ad, "rtol"), column(ad, "max_error_over_L"), "o-", color=color,
                         label=label)
                b.loglog(column(ad, "wall_s"), column(ad, "max_error_over_L"), "o-", color=color,
                         label=f"{label} adaptive")
            if fx:
                b.loglog(column(fx, "wall_s"), column(fx, "max_error_over_L"), "s--", color=color,
                         label=f"{label} fixed dt")
        ad = [r for r in rows if r["case"] == case and r["kind"] == "adaptive"]
        if ad:
            r0 = max(column(ad, "rtol"))
            e0 = max(column(ad, "max_error_over_L"))
            xs = sorted(set(column(ad, "rtol")))
            a.loglog(xs, [e0 * (x / r0) ** (2.0 / 3.0) for x in xs], "k:", label="rtol^(2/3)")
        a.set_title(f"{case}: error vs rtol")
        a.set_xlabel("rtol")
        a.set_ylabel("max tip error / L")
        a.grid(alpha=0.3, which="both")
        a.legend(fontsize=8)
        b.set_title(f"{case}: error vs wall time")
        b.set_xlabel("wall time [s]")
        b.set_ylabel("max tip error / L")
        b.grid(alpha=0.3, which="both")
        b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out_dir}/dynamics_adaptive.png", dpi=110)
    plt.close(fig)
    return True


def main(out_dir):
    written = []
    # --adaptive-only writes step 9's files alone.
    if os.path.exists(f"{out_dir}/release.csv"):
        plot_release(out_dir)
        plot_energy(out_dir)
        plot_orders(out_dir)
        written += ["dynamics_release.png", "dynamics_energy.png", "dynamics_orders.png"]
    if plot_voltage_step(out_dir):
        written.append("dynamics_voltage_step.png")
    if plot_pwm(out_dir):
        written.append("dynamics_pwm.png")
    if plot_adaptive(out_dir):
        written.append("dynamics_adaptive.png")
    print(f"wrote in {out_dir}: {', '.join(written)}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
