#!/usr/bin/python3
"""Writes the main job's report: OUT/report.html (and its Markdown twin OUT/report.md).

Usage: /usr/bin/python3 scripts/make_report.py OUT_DIR [--root REPO]

Reads what scripts/validate.sh and the validation programs wrote into OUT_DIR:
  timing.csv           program,exit_code,seconds,plot_script,plot_exit_code,plot_seconds
  run_info.csv         key,value (started_utc, total_seconds, build_seconds, build_dir, ...)
  <program>/gates.csv  program,gate,measured,bound,passed   (validation/common/gates.hpp)
  <program>/log.txt, <program>/*.png and a few known tables (fig5_table.csv,
  fig6_radius.csv, table1_grasp.csv, fig8_force.csv, crosscheck.csv, convergence.csv,
  shapes_summary.csv, free_vibration.csv, dt_order.csv, quasi_static_order.csv,
  dynamic_crosscheck_summary.csv, dynamic_dt_study.csv, dynamic_h_study.csv, heavy_rod.csv,
  heavy_rod_small_slope.csv, propped.csv, balance.csv, contact_crosscheck_summary.csv) when present.
Without timing.csv every sub-folder holding a gates.csv is reported.

The report reads the way a reviewer reads: the verdict first, then a dashboard of the
headline numbers (the paper's figures and table against the model, the cross-check's worst
differences, the observed orders, the speed), the failed gates (if any), then each
program's plots and key table, and at the end the full gate table, folded, with a filter to
failures (the failed gates are also listed in full near the top, so nothing depends on the
script). It fits a laptop screen without horizontal scrolling: wide tables scroll inside
their own box. Every image has alt text. The HTML is self-contained with relative <img>
links to the PNGs; the Markdown twin has the same sections in the same order.
Exit code: 0 when every gate passed and every program and plot succeeded, 1 otherwise,
2 when the report could not be written. Standard library only.
"""
import csv
import datetime
import html
import html.parser
import os
import platform
import statistics
import subprocess
import sys
from pathlib import Path

# Tables longer than this are cut in the report (the CSV file is linked in full).
MAX_TABLE_ROWS = 40
# Temperatures [degC] at which the Fig. 6 radius curves are summarized.
FIG6_TEMPERATURES_DEGC = (25, 50, 75, 100, 125, 150)

STYLE = """
*, *::before, *::after { box-sizing: border-box; }
body { font-family: system-ui, sans-serif; margin: 0 auto; padding: 0.8em 1.2em 2em; max-width: 1180px;
       color: #222; line-height: 1.4; overflow-wrap: break-word; }
h1 { margin: 0.2em 0 0.1em; font-size: 1.7em; }
h2 { margin-top: 1.8em; border-bottom: 1px solid #ddd; padding-bottom: 0.15em; }
h3 { margin: 1.1em 0 0.3em; font-size: 1.05em; }
.verdict { padding: 0.5em 0.9em; border-radius: 6px; margin: 0.4em 0 0.6em; }
.verdict h1 { margin: 0; }
.verdict p { margin: 0.2em 0 0; }
.verdict-pass { background: #e3f4e3; border-left: 10px solid #2e9b2e; }
.verdict-fail { background: #fbe3e3; border-left: 10px solid #c62828; }
.cards { display: grid; grid-template-columns: repeat(auto-fill, minmax(340px, 1fr)); gap: 0.7em; margin: 0.6em 0; }
.card.wide { grid-column: span 2; }
@media (max-width: 760px) { .card.wide { grid-column: auto; } }
.card { border: 1px solid #d6d6d6; border-radius: 6px; padding: 0.5em 0.7em; background: #fafafa; min-width: 0; }
.card h3 { margin: 0 0 0.25em; font-size: 0.95em; }
.card .big { font-size: 1.35em; font-weight: 600; margin: 0.1em 0; }
.card p { margin: 0.2em 0; font-size: 0.88em; }
.card table { font-size: 0.8em; margin: 0.3em 0; }
.card th, .card td { padding: 2px 5px; }
.scroll { overflow-x: auto; max-width: 100%; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.86em; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.pass, span.pass { background: #d9f2d9; color: #145214; font-weight: bold; }
td.fail, span.fail { background: #f8d0d0; color: #8a1010; font-weight: bold; }
tr.group th { background: #e4e9f2; }
.badge { font-size: 0.8em; padding: 0 0.35em; border-radius: 3px; white-space: nowrap; }
figure { margin: 0.6em 0; }
img { max-width: 100%; height: auto; border: 1px solid #ddd; }
.plots { display: grid; grid-template-columns: repeat(auto-fit, minmax(420px, 1fr)); gap: 0.6em; }
.shapes { display: grid; grid-template-columns: repeat(auto-fill, minmax(260px, 1fr)); gap: 0.5em; }
figcaption { font-size: 0.85em; color: #555; }
pre { background: #f7f7f7; padding: 0.6em; overflow-x: auto; font-size: 0.8em; max-height: 30em; white-space: pre-wrap; }
.note { color: #666; font-size: 0.9em; }
nav ul { columns: 2 300px; padding-left: 1.2em; }
details { margin: 0.5em 0; }
summary { cursor: pointer; font-weight: 600; }
.filter { margin: 0.5em 0; display: flex; flex-wrap: wrap; gap: 1em; align-items: center; }
"""

# The gate table's filter: failures only and/or a text match; runs without any library.
FILTER_SCRIPT = """
(function () {
  var only = document.getElementById('gate-only-failed');
  var text = document.getElementById('gate-text');
  var count = document.getElementById('gate-shown');
  function apply() {
    var q = text.value.toLowerCase(), shown = 0;
    document.querySelectorAll('#gate-table tr.gate').forEach(function (tr) {
      var show = (!only.checked || tr.classList.contains('failed')) &&
                 (q === '' || tr.textContent.toLowerCase().indexOf(q) >= 0);
      tr.hidden = !show;
      if (show) shown++;
    });
    document.querySelectorAll('#gate-table tr.group').forEach(function (tr) {
      var n = 0, row = tr.nextElementSibling;
      while (row && !row.classList.contains('group')) { if (!row.hidden) n++; row = row.nextElementSibling; }
      tr.hidden = n === 0;
    });
    count.textContent = shown + ' shown';
  }
  only.addEventListener('change', apply);
  text.addEventListener('input', apply);
  apply();
})();
"""

VOID_ELEMENTS = {"meta", "img", "br", "hr", "link", "input", "col", "source", "wbr"}

# Alt text of the known plots (the figure a reviewer compares with the paper).
PLOT_DESCRIPTIONS = {
    "fig5.png": "Fig. 5: TCA elongation against temperature for each TCA, load, material and f12 form",
    "fig6.png": "Fig. 6: inner-edge bending radius against temperature of the circular and square manipulators",
    "table1.png": "Table I: grasp temperature against grasped mass, model curves with the measured and the "
                  "paper's values",
    "fig8.png": "Fig. 8: blocked-tip force against temperature for each material",
    "measured_tca.png": "Measured TCA: force against strain of a nylon 6,6 monocoil at 25 and 120 degC, model "
                        "(measured and paper fiber diameter) against the measured isometric tests, nominal and "
                        "fitted parameters, and the fitted values beside the published ranges",
    "crosscheck.png": "Cross-check: difference between the Cosserat shooting and the beam FE solutions against the "
                      "number of elements, per scenario",
    "convergence.png": "Convergence: FE error against element size per scenario and element order, with the "
                       "observed orders",
    "dynamics_release.png": "Rod dynamics: tip trajectory and energies of the released steel cantilever",
    "dynamics_energy.png": "Rod dynamics: energy, work in, dissipated energy and balance residual under a "
                           "tip-force pulse, undamped and damped",
    "dynamics_voltage_step.png": "Rod dynamics: voltage step on the circular manipulator, TCA "
    "temperature against the closed-form step response and the tip settling to the static answer",
    "dynamics_pwm.png": "Rod dynamics: PWM-driven three-TCA rod in 3-D, TCA temperatures against the "
    "closed-form PWM response, the tip against the static tip at the instantaneous temperatures, and the "
    "tip path across the rod's axis",
    "dynamics_orders.png": "Rod dynamics: errors against dt (frequencies, energy drift and balance, forced "
                           "trajectory) and the quasi-static gaps (tip-force ramp, heating ramp, PWM drive) "
                           "against the drive rate, with observed orders",
    "dynamic_crosscheck_trajectories.png": "Dynamic cross-check: tip trajectories of the shooting and FE dynamics "
                                           "at the finest dt per case, and their distance over time",
    "dynamic_crosscheck_dt.png": "Dynamic cross-check: max-over-time difference of the two methods against dt per "
                                 "case, with each method's own time error",
    "dynamic_crosscheck_h.png": "Dynamic cross-check: time-extrapolated difference against the FE element size, "
                                "linear and quadratic elements",
    "dynamic_crosscheck_energy.png": "Dynamic cross-check: kinetic and potential energies of both methods over time",
    "contact_heavy_rod.png": "Contact: the heavy rod's shapes over the floor for each gap H with the closed-form "
                             "free span and touchdown point, and the clamp-moment error against the refinement "
                             "level of both methods with the observed slope",
    "contact_onset.png": "Contact: sweeps across contact onset, tip path and contact force against the load, with "
                         "the closed form of the cantilever on a cylinder",
}


class _TagChecker(html.parser.HTMLParser):
    """Checks that every non-void element is closed, in order (well-formedness of the tags)."""

    def __init__(self):
        super().__init__()
        self.stack, self.errors = [], []

    def handle_starttag(self, tag, attrs):
        if tag not in VOID_ELEMENTS:
            self.stack.append((tag, self.getpos()))

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1][0] != tag:
            self.errors.append(f"line {self.getpos()[0]}: </{tag}> does not close "
                               f"{self.stack[-1] if self.stack else 'anything'}")
        else:
            self.stack.pop()


def html_problems(text):
    """Tag-balance errors of an HTML document (empty when well formed)."""
    checker = _TagChecker()
    checker.feed(text)
    checker.close()
    return checker.errors + [f"<{tag}> opened at line {pos[0]} is never closed" for tag, pos in checker.stack]


def read_csv(path):
    """Rows of a CSV file as dicts (empty list when the file is missing or unreadable)."""
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except (OSError, csv.Error):
        return []


def read_key_values(path):
    return {row["key"]: row["value"] for row in read_csv(path) if "key" in row and "value" in row}


def command_output(args, cwd=None):
    try:
        return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=20,
                              check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def machine_info():
    def lines(path):
        try:
            with open(path) as f:
                return f.read().splitlines()
        except OSError:
            return []

    cpu = next((line.split(":", 1)[1].strip() for line in lines("/proc/cpuinfo") if line.startswith("model name")), "")
    memory = ""
    for line in lines("/proc/meminfo"):
        if line.startswith("MemTotal:"):
            try:
                memory = f"{int(line.split()[1]) / 1024 ** 2:.1f} GiB"
            except (IndexError, ValueError):
                pass
    os_name = platform.platform()
    for line in lines("/etc/os-release"):
        if line.startswith("PRETTY_NAME="):
            os_name = line.split("=", 1)[1].strip().strip('"') + f" ({platform.release()})"
    return {"CPU": cpu or platform.processor() or "unknown", "cores": str(os.cpu_count() or "unknown"),
            "memory": memory or "unknown", "OS": os_name, "python": platform.python_version()}


def commit_info(root):
    if not root:
        return "unknown"
    sha = command_output(["git", "-C", str(root), "rev-parse", "--short", "HEAD"])
    if not sha:
        return "unknown"
    dirty = command_output(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"])
    return sha + (" + uncommitted changes" if dirty else "")


def is_number(text):
    try:
        float(text)
        return True
    except (TypeError, ValueError):
        return False


def number(text):
    """float(text), or None when it is not a number."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def fmt_cell(text):
    """Numbers with many digits are shortened to 6 significant digits for reading."""
    if is_number(text) and len(str(text)) > 10:
        return f"{float(text):.6g}"
    return str(text)


def esc(text):
    return html.escape(str(text))


def html_table(header, rows, numeric=True):
    """A table in a horizontal scroll box (wide tables never widen the page)."""
    out = ['<div class="scroll"><table>', "<tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>"]
    for row in rows:
        cells = []
        for v in row:
            cls = ' class="num"' if numeric and is_number(v) else ""
            cells.append(f"<td{cls}>{esc(fmt_cell(v))}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table></div>")
    return "\n".join(out)


def md_escape(s):
    return str(s).replace("|", "\\|").replace("\n", " ")


def md_table(header, rows):
    lines = ["| " + " | ".join(md_escape(h) for h in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(md_escape(fmt_cell(v)) for v in row) + " |" for row in rows]
    return "\n".join(lines)


def csv_section(path, title, rel, columns=None):
    """A CSV file as a table (cut at MAX_TABLE_ROWS rows; only `columns` when given, those
    present): (html, markdown)."""
    rows = read_csv(path)
    if not rows:
        return "", ""
    header = [c for c in columns if c in rows[0]] if columns else list(rows[0].keys())
    shown = [[r.get(h, "") or "" for h in header] for r in rows[:MAX_TABLE_ROWS]]
    if len(rows) > MAX_TABLE_ROWS:
        note = f"first {MAX_TABLE_ROWS} of {len(rows)} rows; full table:"
    else:
        note = "file:"
    cut = f'<p class="note">{note} <a href="{esc(rel)}">{esc(path.name)}</a></p>'
    h = f"<h3>{esc(title)}</h3>\n{html_table(header, shown)}\n{cut}"
    m = f"#### {title}\n\n{md_table(header, shown)}\n\n{note} [{path.name}]({rel})\n"
    return h, m


def fig6_summary(path, rel):
    """fig6_radius.csv summarized: radius [mm] per manipulator and material at a few temperatures."""
    rows = read_csv(path)
    if not rows:
        return "", ""
    curves = {}
    for r in rows:
        key = (r.get("manipulator", "?"), r.get("material", "?"))
        t = number(r.get("temperature_degC"))
        if t is None:
            continue
        radius = r.get("bending_radius_m", "")
        if r.get("converged", "1") != "1":
            value = "not converged"
        else:
            value = f"{1e3 * float(radius):.2f}" if is_number(radius) else "straight"
        curves.setdefault(key, {})[round(t, 6)] = value
    header = ["manipulator", "material"] + [f"{t} degC" for t in FIG6_TEMPERATURES_DEGC]
    table = [[k[0], k[1]] + [v.get(float(t), "") for t in FIG6_TEMPERATURES_DEGC] for k, v in sorted(curves.items())]
    title = "Fig. 6: three-point inner-edge bending radius [mm] (summary)"
    h = (f"<h3>{esc(title)}</h3>\n{html_table(header, table)}\n"
         f'<p class="note">{len(rows)} points; full table: <a href="{esc(rel)}">{esc(path.name)}</a></p>')
    m = f"#### {title}\n\n{md_table(header, table)}\n\n{len(rows)} points; full table: [{path.name}]({rel})\n"
    return h, m


# Known tables: (file name, title[, columns shown]); fig6_radius.csv is summarized separately.
KNOWN_TABLES = [
    ("fig5_table.csv", "Fig. 5: TCA onset temperature and elongation at 160 degC"),
    ("table1_grasp.csv", "Table I: grasping (paper comparison)",
     ["material", "f12_form", "calibration", "mass_g", "temperature_degC", "paper_degC", "measured_degC",
      "blocked_force_rel_error", "iterations", "converged"]),
    ("measured_tca_summary.csv", "Measured TCA: passive stiffness and elongation at 1 N, model against measurement"),
    ("measured_tca_fit.csv", "Measured TCA: fitted shear modulus and expansion beside the published ranges"),
    ("fig8_force.csv", "Fig. 8: force (paper comparison)",
     ["material", "temperature_degC", "force_N", "wire_taut", "pinned_force_N", "free_tip_x_m", "free_tip_z_m"]),
    ("crosscheck.csv", "Cross-check: Cosserat shooting vs beam FE",
     ["scenario", "elements", "order", "tip_diff_over_L", "rotation_diff_rad", "max_tension_diff_N",
      "cosserat_time_s", "fe_time_s", "converged"]),
    ("convergence.csv", "Convergence: error vs discretization",
     ["scenario", "order", "elements", "error_m", "observed_order", "richardson_order", "range", "converged"]),
    ("free_vibration.csv", "Rod dynamics: cantilever frequencies against Euler-Bernoulli and Timoshenko",
     ["mass_ratio", "mode", "dt_s", "grid_steps", "omega_rad_s", "euler_bernoulli_rad_s", "error_vs_eb",
      "timoshenko_correction", "error_vs_timoshenko", "error_vs_timoshenko_plus_scheme"]),
    ("dt_order.csv", "Rod dynamics: errors against dt and observed orders"),
    ("quasi_static_order.csv", "Rod dynamics: quasi-static gap against the ramp rate"),
    ("heated_ramp_order.csv", "Rod dynamics: heated manipulator, gap to the static solution against the ramp rate"),
    ("pwm_quasi_static_order.csv", "Rod dynamics: PWM-driven three-TCA rod, gap to the quasi-static tip against "
     "the drive rate"),
    ("dynamic_crosscheck_summary.csv", "Dynamic cross-check: finest settings per case"),
    ("dynamic_dt_study.csv", "Dynamic cross-check: difference and own time errors against dt",
     ["case", "dt_s", "shooting_steps", "fe_elements", "difference_over_L", "at_t_s", "shooting_time_error_over_L",
      "fe_time_error_over_L", "shooting_wall_s", "fe_wall_s"]),
    ("dynamic_h_study.csv", "Dynamic cross-check: difference against the FE element size (extrapolated in dt)"),
    ("heavy_rod_small_slope.csv", "Contact: heavy rod on a floor, closed form against the planar reference "
     "(small-slope error)"),
    ("heavy_rod.csv", "Contact: heavy rod on a floor, refinement ladders of both methods",
     ["H_m", "method", "level", "converged", "base_force_N", "base_moment_Nm", "touchdown_s_m",
      "force_error_vs_ref", "moment_error_vs_ref", "moment_error_vs_closed", "observed_order_moment", "message"]),
    ("propped.csv", "Contact: propped cantilever, sphere reaction against P (3 L - a) / (2 a)"),
    ("balance.csv", "Contact: global balance of each solve",
     ["scenario", "method", "level", "converged", "has_base_reaction", "force_imbalance_N", "force_bound_N",
      "moment_imbalance_Nm", "moment_bound_Nm", "message"]),
    ("contact_crosscheck_summary.csv", "Contact: shooting against FE at the finest levels"),
    ("shapes_summary.csv", "Suite scenarios: tip, global equilibrium (relative imbalance), timing",
     ["scenario", "status", "iterations", "tip_x_m", "tip_y_m", "tip_z_m", "bending_radius_m", "load_scale_N",
      "force_imbalance_rel", "moment_imbalance_rel", "imbalance_8_steps", "imbalance_16_steps", "wall_time_s",
      "reason"]),
]


# ---------------------------------------------------------------------------------------------
# The dashboard: one card per headline, each computed from a program's CSV (None when absent).
# A card is (title, headline, lines, table, anchor): table = (header, rows) or None.


def _span(values):
    values = [v for v in values if v is not None]
    return (min(values), max(values)) if values else None


def card_table1(out_dir):
    rows = read_csv(out_dir / "validate_table1_grasp" / "table1_grasp.csv")
    if not rows:
        return None
    groups = {}
    for r in rows:
        t, paper, measured = number(r.get("temperature_degC")), number(r.get("paper_degC")), number(
            r.get("measured_degC"))
        if t is None:
            continue
        key = (r.get("material", "?"), r.get("f12_form", "?"), r.get("calibration", "none"))
        g = groups.setdefault(key, {"paper": [], "measured": []})
        if paper is not None:
            g["paper"].append(abs(t - paper))
        if measured is not None:
            g["measured"].append(abs(t - measured))
    table = []
    for (material, form, cal), g in groups.items():
        worst_paper = max(g["paper"]) if g["paper"] else None
        worst_measured = max(g["measured"]) if g["measured"] else None
        table.append([f"{material}, f12 {form}" + ("" if cal == "none" else f", {cal}"),
                      f"{worst_paper:.1f}" if worst_paper is not None else "",
                      f"{worst_measured:.1f}" if worst_measured is not None else ""])
    if not table:
        return None
    best = min(table, key=lambda row: float(row[1]) if row[1] else float("inf"))
    calibrated = [float(row[1]) for (key, row) in zip(groups, table) if key[2] != "none" and row[1]]
    uncalibrated = [float(row[1]) for (key, row) in zip(groups, table) if key[2] == "none" and row[1]]
    if calibrated and uncalibrated:
        headline = (f"{min(calibrated):.1f} degC calibrated, {min(uncalibrated):.1f} to "
                    f"{max(uncalibrated):.1f} degC uncalibrated")
    else:
        headline = f"best {best[1]} degC" if best[1] else "no paper values"
    return ("Table I: grasp temperature, model vs paper", headline,
            [f"worst |model - paper| over the masses per configuration; best: {best[0]}"],
            (["configuration", "vs paper [degC]", "vs measured [degC]"], table),
            "validate_table1_grasp")


def card_fig5(out_dir):
    rows = read_csv(out_dir / "validate_fig5_tca" / "fig5_table.csv")
    if not rows:
        return None
    onset = _span(number(r.get("onset_temperature_degC")) for r in rows)
    elong = _span(number(r.get("elongation_at_160_degC_m")) for r in rows)
    lines = [f"{len(rows)} curves (TCA x load x material x f12 form)"]
    if elong:
        lines.append(f"elongation at 160 degC: {1e3 * elong[0]:.1f} to {1e3 * elong[1]:.1f} mm")
    return ("Fig. 5: TCA onset temperature",
            f"{onset[0]:.1f} to {onset[1]:.1f} degC" if onset else "-", lines, None, "validate_fig5_tca")


def card_measured_tca(out_dir):
    rows = read_csv(out_dir / "validate_measured_tca" / "measured_tca_summary.csv")
    fits = read_csv(out_dir / "validate_measured_tca" / "measured_tca_fit.csv")
    if not rows:
        return None
    nominal = [r for r in rows if r.get("tca") == "measured" and r.get("parameters") == "nominal"]
    label = {"measured": "measured d0", "paper-d0": "paper d0 = 2DL/l"}
    lines = []
    for r in rows:
        if r.get("parameters") == "nominal":
            lines.append(f"{label.get(r['tca'], r['tca'])}, nominal: {number(r.get('passive_stiffness_N_mm')):.3f} N/mm "
                         f"(measured {number(r.get('measured_passive_stiffness_N_mm')):.3f})")
    for f in fits:
        if f.get("parameter") == "shear_modulus":
            lines.append(f"{label.get(f['tca'], f['tca'])}, fitted G = {1e-9 * number(f.get('value')):.3g} GPa "
                         f"(published {1e-9 * number(f.get('published_lo')):.3g} to "
                         f"{1e-9 * number(f.get('published_hi')):.3g})")
    headline = (f"stiffness ratio {number(nominal[0].get('stiffness_ratio')):.2f}" if nominal else "-")
    return ("Measured TCA: nylon monocoil, model vs isometric tests", headline, lines, None,
            "validate_measured_tca")


def card_fig6(out_dir):
    rows = read_csv(out_dir / "validate_fig6_radius" / "fig6_radius.csv")
    if not rows:
        return None
    hottest = {}
    not_converged = 0
    for r in rows:
        t = number(r.get("temperature_degC"))
        if r.get("converged", "1") != "1":
            not_converged += 1
        key = (r.get("manipulator", "?"), r.get("material", "?"))
        if t is not None and (key not in hottest or t > hottest[key][0]):
            hottest[key] = (t, number(r.get("bending_radius_m")))
    table = [[f"{m} / {mat}", f"{t:g}", f"{1e3 * radius:.2f}" if radius is not None else "straight"]
             for (m, mat), (t, radius) in sorted(hottest.items())]
    radii = [row[2] for row in table if row[2] != "straight"]
    return ("Fig. 6: bending radius at the hottest point",
            f"{min(radii, key=float)} to {max(radii, key=float)} mm" if radii else "-",
            [f"{len(rows)} points, {not_converged} not converged"],
            (["manipulator / material", "T [degC]", "radius [mm]"], table), "validate_fig6_radius")


def card_fig8(out_dir):
    rows = read_csv(out_dir / "validate_fig8_force" / "fig8_force.csv")
    if not rows:
        return None
    hottest = {}
    for r in rows:
        t, f = number(r.get("temperature_degC")), number(r.get("force_N"))
        key = r.get("material", "?")
        if t is not None and (key not in hottest or t > hottest[key][0]):
            hottest[key] = (t, f)
    table = [[m, f"{t:g}", f"{1e3 * f:.1f}" if f is not None else ""] for m, (t, f) in sorted(hottest.items())]
    forces = [float(row[2]) for row in table if row[2]]
    return ("Fig. 8: blocked force at the hottest point",
            f"{min(forces):.1f} to {max(forces):.1f} mN" if forces else "-",
            [f"{len(rows)} points"], (["material", "T [degC]", "force [mN]"], table), "validate_fig8_force")


def card_crosscheck(out_dir):
    rows = read_csv(out_dir / "validate_crosscheck" / "crosscheck.csv")
    if not rows:
        return None
    finest = {}
    for r in rows:
        e = number(r.get("elements"))
        key = (r.get("scenario", "?"), r.get("order", "?"))
        if e is not None and (key not in finest or e > number(finest[key].get("elements"))):
            finest[key] = r
    if not finest:
        return None

    def worst(column, order=None):
        best = None
        for (scenario, o), r in finest.items():
            v = number(r.get(column))
            if (order is None or o == order) and v is not None and (best is None or v > best[0]):
                best = (v, scenario, o, r.get("elements", "?"))
        return best

    orders = sorted({o for _, o in finest})
    table = []
    for o in orders:
        w = worst("tip_diff_over_L", o)
        if w:
            table.append([f"tip difference / L, order {o}", f"{w[0]:.2e}", f"{w[1]} ({w[3]} el.)"])
    for label, column in (("rotation [rad]", "rotation_diff_rad"), ("tension [N]", "max_tension_diff_N")):
        w = worst(column)
        if w:
            table.append([label, f"{w[0]:.2e}", f"{w[1]} (order {w[2]}, {w[3]} el.)"])
    # The headline: the highest element order's worst tip difference (the FE default is 2).
    tip = worst("tip_diff_over_L", orders[-1]) if orders else None
    lines = [f"{len({k[0] for k in finest})} scenarios, each at its finest mesh"]
    return ("Cross-check: shooting vs FE, worst difference",
            f"{tip[0]:.1e} L (order {orders[-1]})" if tip else "-", lines,
            (["quantity", "worst", "where"], table), "validate_crosscheck")


def card_orders(out_dir):
    rows = read_csv(out_dir / "validate_convergence" / "convergence.csv")
    table = []
    per_order = {}
    for r in rows:
        o = r.get("order", "?")
        v = number(r.get("asymptotic_order"))
        if v is None:
            continue
        per_order.setdefault(o, {})[r.get("scenario", "?")] = v
    for o, by_scenario in sorted(per_order.items()):
        vals = list(by_scenario.values())
        expected = 2 * int(o) if o.isdigit() else None
        table.append([f"FE order {o}" + (f" (expected {expected})" if expected else ""), f"{min(vals):.3f}",
                      f"{max(vals):.3f}", str(len(vals))])
    imbalance = []
    for g in read_csv(out_dir / "validate_shapes" / "gates.csv"):
        if "observed order" in g.get("gate", "") and number(g.get("measured")) is not None:
            imbalance.append(number(g.get("measured")))
    if imbalance:
        table.append(["shooting RK4, equilibrium imbalance (expected 4)", f"{min(imbalance):.3f}",
                      f"{max(imbalance):.3f}", str(len(imbalance))])
    if not table:
        return None
    head = "; ".join(f"order {o}: {min(v.values()):.2f} to {max(v.values()):.2f}"
                     for o, v in sorted(per_order.items())) or f"RK4: {min(imbalance):.2f} to {max(imbalance):.2f}"
    return ("Observed orders of convergence", head,
            ["asymptotic orders over the scenarios (min, max)"], (["discretization", "min", "max", "cases"], table),
            "validate_convergence" if per_order else "validate_shapes")


def card_dynamics(out_dir):
    rows = read_csv(out_dir / "validate_dynamics" / "free_vibration.csv")
    if not rows:
        return None
    table = [[r["mass_ratio"], r["mode"], r["dt_s"], f"{number(r['error_vs_eb']):+.2e}",
              f"{number(r['error_vs_timoshenko_plus_scheme']):+.2e}"] for r in rows]
    worst = max(abs(number(r["error_vs_eb"])) for r in rows)
    return ("Rod dynamics: cantilever frequencies vs Euler-Bernoulli", f"worst |error| {worst:.1e}",
            ["slender steel cantilever, released from a small tip deflection; frequencies fitted to the "
             "modal projections; last column: against Timoshenko shifted by BDF-alpha's own period error"],
            (["tip mass ratio", "mode", "dt [s]", "vs EB", "vs Timoshenko + scheme"], table), "validate_dynamics")


def card_dynamic_crosscheck(out_dir):
    rows = read_csv(out_dir / "validate_dynamic_crosscheck" / "dynamic_crosscheck_summary.csv")
    if not rows:
        return None
    table, worst = [], None
    for r in rows:
        if r.get("status") != "run":
            table.append([r.get("case", "?"), f"pending: {r.get('reason', '')}", "", ""])
            continue
        d, x = number(r.get("difference_over_L")), number(r.get("extrapolated_difference_over_L"))
        table.append([r.get("case", "?"), r.get("finest_dt_s", ""), f"{d:.1e}" if d is not None else "-",
                      f"{x:.1e}" if x is not None else "-"])
        if r.get("bound_over_L") and d is not None and (worst is None or d > worst[0]):
            worst = (d, r.get("case", "?"))
    return ("Dynamic cross-check: shooting vs FE over time",
            f"worst {worst[0]:.1e} L ({worst[1]})" if worst else "-",
            ["max over time of the tip distance at the finest dt; extrapolated: both runs Richardson-extrapolated "
             "in dt (spatial + model difference)"],
            (["case", "finest dt [s]", "difference / L", "extrapolated / L"], table), "validate_dynamic_crosscheck")


def card_contact(out_dir):
    """validate_contact: the heavy rod's closed-form (small-slope) error per gap and each method's finest
    clamp-moment error against the planar reference."""
    small = read_csv(out_dir / "validate_contact" / "heavy_rod_small_slope.csv")
    if not small:
        return None
    ladder = read_csv(out_dir / "validate_contact" / "heavy_rod.csv")
    finest = {}
    for r in ladder:
        key = (r.get("H_m"), r.get("method"))
        lvl = number(r.get("level"))
        if lvl is not None and (key not in finest or lvl > number(finest[key].get("level"))):
            finest[key] = r
    table = []
    for r in small:
        h = r.get("H_m")
        e = number(r.get("moment_error"))
        row = [f"{1e3 * number(h):.3g}" if number(h) is not None else "?", f"{e:.1e}" if e is not None else "-"]
        for method in ("cosserat", "fe"):
            f = finest.get((h, method))
            v = number(f.get("moment_error_vs_ref")) if f and f.get("converged") == "1" else None
            row.append(f"{v:.1e}" if v is not None else "not converged" if f else "-")
        table.append(row)
    balance = read_csv(out_dir / "validate_contact" / "balance.csv")
    reported = sum(1 for r in balance if r.get("has_base_reaction") == "1")
    return ("Contact: heavy rod on a floor (clamp moment)", f"{len(small)} gaps",
            [f"relative clamp-moment distance to the Cosserat planar reference: the closed form's (its shear "
             f"and extension; its small-slope error is zero for the moment), each method's at its finest level; "
             f"base reaction reported in {reported} of {len(balance)} balance solves"],
            (["H [mm]", "closed form", "shooting", "FE"], table), "validate_contact")


def card_speed(out_dir, timing, run):
    table = []
    shapes = read_csv(out_dir / "validate_shapes" / "shapes_summary.csv")
    times = [number(r.get("wall_time_s")) for r in shapes if number(r.get("wall_time_s")) is not None]
    if times:
        table.append(["shooting solve, suite scenario (median)", f"{1e3 * statistics.median(times):.2f} ms",
                      f"{len(times)} scenarios"])
    cross = read_csv(out_dir / "validate_crosscheck" / "crosscheck.csv")
    cos = {r.get("scenario"): number(r.get("cosserat_time_s")) for r in cross if number(r.get("cosserat_time_s"))}
    if cos:
        table.append(["shooting reference solve (median)", f"{1e3 * statistics.median(cos.values()):.2f} ms",
                      f"{len(cos)} scenarios"])
    fe16 = [number(r.get("fe_time_s")) for r in cross
            if r.get("elements") == "16" and r.get("order") == "2" and number(r.get("fe_time_s")) is not None]
    if fe16:
        table.append(["FE solve, 16 quadratic elements (median)", f"{1e3 * statistics.median(fe16):.2f} ms",
                      f"{len(fe16)} scenarios"])
    program_seconds = [number(t.get("seconds")) for t in timing if number(t.get("seconds")) is not None]
    if program_seconds:
        table.append(["validation programs, all", f"{sum(program_seconds):.1f} s", f"{len(program_seconds)} programs"])
    total = run.get("total_seconds")
    if not table and not total:
        return None
    return ("Speed", f"{total} s in total" if total else "-",
            ["the whole run (build, programs, plots)" if total else "run time unknown"],
            (["what", "time", "over"], table) if table else None, "programs")


def dashboard_cards(out_dir, timing, run):
    cards, errors = [], []
    for make in (card_table1, card_fig5, card_fig6, card_fig8, card_crosscheck, card_orders, card_dynamics,
                 card_dynamic_crosscheck, card_measured_tca, card_contact):
        try:
            c = make(out_dir)
        except (KeyError, ValueError, TypeError, ZeroDivisionError, statistics.StatisticsError) as e:
            errors.append(f"{make.__name__}: {e}")
            c = None
        if c:
            cards.append(c)
    try:
        c = card_speed(out_dir, timing, run)
    except (KeyError, ValueError, TypeError, statistics.StatisticsError) as e:
        errors.append(f"card_speed: {e}")
        c = None
    if c:
        cards.append(c)
    return cards, errors


def gate_badge(counts):
    """'gates 56/56' in green, or the failures in red; empty when the program has no gates."""
    if not counts or not counts[1]:
        return ""
    passed, total = counts
    cls = "pass" if passed == total else "fail"
    return f' <span class="{cls} badge">gates {passed}/{total}</span>'


def card_html(card, gate_counts):
    title, headline, lines, table, anchor = card
    wide = table is not None and len(table[0]) >= 3 and len(table[1]) > 3
    parts = [f'<div class="card{" wide" if wide else ""}"><h3><a href="#{esc(anchor)}">{esc(title)}</a>'
             f"{gate_badge(gate_counts.get(anchor))}</h3>",
             f'<p class="big">{esc(headline)}</p>']
    parts += [f"<p>{esc(line)}</p>" for line in lines]
    if table:
        parts.append(html_table(table[0], table[1], numeric=False))
    parts.append("</div>")
    return "\n".join(parts)


def card_md(card, gate_counts):
    title, headline, lines, table, anchor = card
    counts = gate_counts.get(anchor)
    badge = f" (gates {counts[0]}/{counts[1]})" if counts and counts[1] else ""
    out = [f"### {title}: {headline}{badge}", ""] + [f"- {line}" for line in lines] + [""]
    if table:
        out += [md_table(table[0], table[1]), ""]
    return out


# ---------------------------------------------------------------------------------------------


def program_list(out_dir, timing):
    names = [t["program"] for t in timing]
    for d in sorted(p for p in out_dir.iterdir() if p.is_dir()):
        if d.name not in names and (d / "gates.csv").exists() and not timing:
            names.append(d.name)
    return names


def plot_alt(program, png):
    if png.name.endswith("_shape.png"):
        scenario = png.name[: -len("_shape.png")]
        return f"Deformed shape of the {scenario} scenario: centerline and actuator string paths"
    return PLOT_DESCRIPTIONS.get(png.name, f"Plot {png.stem} of {program}")


def main(argv):
    args = argv[1:]
    root = None
    if "--root" in args:
        i = args.index("--root")
        root = Path(args[i + 1])
        del args[i:i + 2]
    if len(args) != 1:
        print(__doc__)
        return 2
    out_dir = Path(args[0])
    if not out_dir.is_dir():
        print(f"make_report: {out_dir} is not a folder", file=sys.stderr)
        return 2
    timing = read_csv(out_dir / "timing.csv")
    timing_by_name = {t["program"]: t for t in timing}
    run = read_key_values(out_dir / "run_info.csv")
    programs = program_list(out_dir, timing)

    gates = []           # (program, gate, measured, bound, passed)
    problems = []        # program-level failures (exit codes, missing gates, plots)
    per_program = {}
    for name in programs:
        d = out_dir / name
        rows = read_csv(d / "gates.csv")
        per_program[name] = rows
        for r in rows:
            gates.append((r.get("program", name) or name, r.get("gate", ""), r.get("measured", ""),
                          r.get("bound", ""), r.get("passed", "0") == "1"))
        t = timing_by_name.get(name)
        if not rows:
            if t and t.get("exit_code") == "0":
                problems.append(f"{name}: exited 0 but wrote no gates.csv (a validation program records its "
                                "gates through validation/common/gates.hpp)")
            else:
                problems.append(f"{name}: no gates.csv (the program did not finish; see its log)")
        if t and t.get("exit_code", "0") != "0":
            problems.append(f"{name}: exit code {t['exit_code']}")
        if t and t.get("plot_script") and t.get("plot_exit_code", "0") != "0":
            problems.append(f"{name}: plot script {t['plot_script']} failed (exit code {t['plot_exit_code']})")

    failed_gates = [g for g in gates if not g[4]]
    n_failed = len(failed_gates)
    ok = n_failed == 0 and not problems and bool(gates)
    verdict = "PASS" if ok else "FAIL"
    commit = commit_info(root)
    generated = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    if ok:
        verdict_line = f"all {len(gates)} gates of {len(programs)} programs passed"
    elif not gates:
        verdict_line = "no gates were recorded"
    else:
        verdict_line = (f"{n_failed} of {len(gates)} gates failed" +
                        (f"; {len(problems)} program-level problems" if problems else ""))
    run_line = (f"commit {commit}; started {run.get('started_utc', 'unknown')}; "
                f"{run.get('total_seconds', '?')} s in total")
    cards, card_errors = dashboard_cards(out_dir, timing, run)
    machine = machine_info()
    about_items = [
        ("commit", commit),
        ("started", run.get("started_utc", "unknown")),
        ("report written", generated),
        ("total run time", f"{run['total_seconds']} s" if "total_seconds" in run else "unknown"),
        ("build time", f"{run['build_seconds']} s" if "build_seconds" in run else "unknown"),
        ("build", f"{run.get('build_dir', '?')} ({run.get('build_type', '?')}, {run.get('jobs', '?')} jobs)"),
    ] + list(machine.items())

    time_rows = []
    for name in programs:
        t = timing_by_name.get(name, {})
        rows = per_program[name]
        nf = sum(1 for r in rows if r.get("passed") != "1")
        time_rows.append([name, t.get("seconds", "?"), t.get("plot_seconds", "") or "-", t.get("exit_code", "?"),
                          f"{len(rows) - nf}/{len(rows)}"])

    # ----- HTML
    h = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
         '<meta name="viewport" content="width=device-width, initial-scale=1">',
         f"<title>tcasim validation report: {verdict}</title>", f"<style>{STYLE}</style>", "</head>", "<body>"]
    h.append(f'<header id="verdict" class="verdict verdict-{verdict.lower()}">'
             f"<h1>tcasim validation: {verdict}</h1>"
             f"<p><strong>{esc(verdict_line)}</strong></p>"
             f'<p class="note">{esc(run_line)}. Pass/fail is decided by the C++ validation programs '
             "(the same gates ctest runs); this page is written by scripts/make_report.py.</p></header>")
    if problems:
        h.append('<p class="fail">Program-level problems:</p><ul>' +
                 "".join(f"<li>{esc(p)}</li>" for p in problems) + "</ul>")
    h.append('<section id="dashboard"><h2>Headline numbers</h2>')
    gate_counts = {name: (sum(1 for r in rows if r.get("passed") == "1"), len(rows))
                   for name, rows in per_program.items()}
    h.append('<div class="cards">' + "\n".join(card_html(c, gate_counts) for c in cards) + "</div>")
    if card_errors:
        h.append('<p class="note">Cards left out (unexpected table contents): ' + esc("; ".join(card_errors)) + "</p>")
    h.append("</section>")
    if failed_gates:
        h.append(f'<section id="failed-gates"><h2>Failed gates ({n_failed})</h2>')
        h.append(html_table(["program", "gate", "measured", "bound"],
                            [[p, g, m, b] for p, g, m, b, _ in failed_gates], numeric=False))
        h.append("</section>")
    h.append('<nav id="programs"><h2>Programs</h2>')
    h.append(html_table(["program", "run time [s]", "plot time [s]", "exit code", "gates passed"], time_rows))
    h.append("<ul>" + "".join(f'<li><a href="#{esc(n)}">{esc(n)}</a></li>' for n in programs) +
             '<li><a href="#all-gates">all gates</a></li><li><a href="#about">about this run</a></li></ul></nav>')

    md = [f"# tcasim validation: {verdict}", "", f"**{verdict_line}**", "", f"{run_line}.", ""]
    if problems:
        md += ["Program-level problems:", ""] + [f"- {p}" for p in problems] + [""]
    md += ["## Headline numbers", ""]
    for c in cards:
        md += card_md(c, gate_counts)
    if failed_gates:
        md += [f"## Failed gates ({n_failed})", "",
               md_table(["program", "gate", "measured", "bound"], [[p, g, m, b] for p, g, m, b, _ in failed_gates]),
               ""]
    md += ["## Programs", "", md_table(["program", "run time [s]", "plot time [s]", "exit code", "gates passed"],
                                       time_rows), ""]

    # One section per program: its plots, its key tables, its failed gates, its log.
    for name in programs:
        d = out_dir / name
        rows = per_program[name]
        nf = sum(1 for r in rows if r.get("passed") != "1")
        t = timing_by_name.get(name, {})
        status = "pass" if nf == 0 and rows and t.get("exit_code", "0") == "0" else "fail"
        h.append(f'<section id="{esc(name)}"><h2>{esc(name)} <span class="{status}">{status.upper()}</span></h2>')
        h.append(f'<p>{len(rows) - nf} of {len(rows)} gates passed; run time {esc(t.get("seconds", "?"))} s; '
                 f'exit code {esc(t.get("exit_code", "?"))}; <a href="#gates-{esc(name)}">its gates</a></p>')
        md += [f"## {name}: {status.upper()}", "",
               f"{len(rows) - nf} of {len(rows)} gates passed; run time {t.get('seconds', '?')} s; "
               f"exit code {t.get('exit_code', '?')}", ""]
        pngs = sorted(d.glob("*.png")) if d.is_dir() else []
        shapes = [p for p in pngs if p.name.endswith("_shape.png")]
        others = [p for p in pngs if p not in shapes]
        if others:
            h.append('<div class="plots">' + "".join(
                f'<figure><img src="{esc(name + "/" + p.name)}" alt="{esc(plot_alt(name, p))}">'
                f"<figcaption>{esc(plot_alt(name, p))} ({esc(p.name)})</figcaption></figure>" for p in others) +
                "</div>")
            md += [f"![{plot_alt(name, p)}]({name}/{p.name})" for p in others] + [""]
        if shapes:
            h.append('<div class="shapes">' + "".join(
                f'<figure><img src="{esc(name + "/" + p.name)}" alt="{esc(plot_alt(name, p))}">'
                f'<figcaption>{esc(p.name[: -len("_shape.png")])}</figcaption></figure>' for p in shapes) + "</div>")
            vtps = sorted(d.glob("*.vtp"))
            if vtps:
                h.append('<p class="note">VTK PolyData for ParaView: ' +
                         ", ".join(f'<a href="{esc(name + "/" + v.name)}">{esc(v.name)}</a>' for v in vtps) + "</p>")
            md += [f"![{plot_alt(name, p)}]({name}/{p.name})" for p in shapes] + [""]
        for fname, title, *columns in KNOWN_TABLES:
            if (d / fname).exists():
                th, tm = csv_section(d / fname, title, f"{name}/{fname}", columns[0] if columns else None)
                h.append(th)
                md += [tm, ""]
        if (d / "fig6_radius.csv").exists():
            th, tm = fig6_summary(d / "fig6_radius.csv", f"{name}/fig6_radius.csv")
            h.append(th)
            md += [tm, ""]
        mine_failed = [[g.get("gate", ""), g.get("measured", ""), g.get("bound", "")]
                       for g in rows if g.get("passed") != "1"]
        if mine_failed:
            h.append(f"<h3>Failed gates of {esc(name)}</h3>" +
                     html_table(["gate", "measured", "bound"], mine_failed, numeric=False))
            md += [f"#### Failed gates of {name}", "", md_table(["gate", "measured", "bound"], mine_failed), ""]
        known = {entry[0] for entry in KNOWN_TABLES} | {"fig6_radius.csv", "gates.csv"}
        other = [p for p in (sorted(d.glob("*.csv")) if d.is_dir() else [])
                 if p.name not in known and not p.name.endswith("_shape.csv")]
        if other:
            h.append('<p class="note">Other data: ' + ", ".join(
                f'<a href="{esc(name + "/" + p.name)}">{esc(p.name)}</a>' for p in other) + "</p>")
        log = d / "log.txt"
        if log.exists():
            text = log.read_text(errors="replace")
            h.append(f"<details><summary>log ({len(text.splitlines())} lines)</summary>"
                     f'<p class="note"><a href="{esc(name)}/log.txt">log.txt</a></p>'
                     f"<pre>{esc(text)}</pre></details>")
            md += [f"Log: [{name}/log.txt]({name}/log.txt)", ""]
        h.append("</section>")

    # Every gate, folded, grouped by program, with the filter.
    h.append('<section id="all-gates"><h2>All gates</h2>')
    h.append(f"<details{' open' if failed_gates else ''}><summary>all {len(gates)} gates "
             f"({n_failed} failed)</summary>")
    h.append('<div class="filter"><label><input type="checkbox" id="gate-only-failed"'
             f"{' checked' if failed_gates else ''}> failures only</label>"
             '<label>filter <input type="search" id="gate-text" placeholder="gate text"></label>'
             f'<span id="gate-shown" class="note">{len(gates)} gates</span></div>')
    h.append('<div class="scroll"><table id="gate-table">'
             "<tr><th>gate</th><th>measured</th><th>bound</th><th>verdict</th></tr>")
    for name in programs:
        mine = [g for g in gates if g[0] == name] or []
        nf = sum(1 for g in mine if not g[4])
        h.append(f'<tr class="group" id="gates-{esc(name)}"><th colspan="4">{esc(name)}: '
                 f"{len(mine) - nf} of {len(mine)} passed</th></tr>")
        for _, gate, measured, bound, passed in mine:
            cls = "pass" if passed else "fail"
            h.append(f'<tr class="gate{"" if passed else " failed"}"><td>{esc(gate)}</td><td>{esc(measured)}</td>'
                     f'<td>{esc(bound)}</td><td class="{cls}">{"PASS" if passed else "FAIL"}</td></tr>')
    others = [g for g in gates if g[0] not in programs]
    for prog, gate, measured, bound, passed in others:
        cls = "pass" if passed else "fail"
        h.append(f'<tr class="gate{"" if passed else " failed"}"><td>{esc(prog)}: {esc(gate)}</td>'
                 f'<td>{esc(measured)}</td><td>{esc(bound)}</td><td class="{cls}">{"PASS" if passed else "FAIL"}</td>'
                 "</tr>")
    h.append("</table></div></details></section>")
    md += ["## All gates", "",
           md_table(["program", "gate", "measured", "bound", "verdict"],
                    [[p, g, m, b, "PASS" if ok_ else "**FAIL**"] for p, g, m, b, ok_ in gates]), ""]

    h.append('<section id="about"><h2>About this run</h2>')
    h.append(html_table(["item", "value"], about_items, numeric=False))
    h.append("</section>")
    md += ["## About this run", "", md_table(["item", "value"], about_items), ""]
    h += [f"<script>{FILTER_SCRIPT}</script>", "</body>", "</html>", ""]

    document = "\n".join(h)
    errors = html_problems(document)
    if errors:
        print("make_report: the generated HTML is not well formed:\n  " + "\n  ".join(errors[:10]), file=sys.stderr)
        return 2
    try:
        (out_dir / "report.html").write_text(document)
        (out_dir / "report.md").write_text("\n".join(md) + "\n")
    except OSError as e:
        print(f"make_report: cannot write the report: {e}", file=sys.stderr)
        return 2
    print(f"make_report: {out_dir / 'report.html'}: {len(gates)} gates, {len(gates) - n_failed} passed, "
          f"{n_failed} failed; {len(problems)} program-level problems")
    for p in problems:
        print(f"make_report:   {p}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
