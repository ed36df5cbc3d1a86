#!/usr/bin/python3
"""Writes the main job's report: OUT/report.html (and its Markdown twin OUT/report.md).

Usage: /usr/bin/python3 scripts/make_report.py OUT_DIR [--root REPO]

Reads what scripts/validate.sh and the validation programs wrote into OUT_DIR:
  timing.csv           program,exit_code,seconds,plot_script,plot_exit_code,plot_seconds
  run_info.csv         key,value (started_utc, total_seconds, build_seconds, build_dir, ...)
  <program>/gates.csv  program,gate,measured,bound,passed   (validation/common/gates.hpp)
  <program>/log.txt, <program>/*.png and a few known tables (fig5_table.csv,
  fig6_radius.csv, crosscheck.csv, convergence.csv, shapes_summary.csv) when present.
Without timing.csv every sub-folder holding a gates.csv is reported.
The report is self-contained HTML with relative <img> links to the PNGs.
Exit code: 0 when every gate passed and every program and plot succeeded, 1 otherwise,
2 when the report could not be written. Standard library only.
"""
import csv
import datetime
import html
import html.parser
import os
import platform
import subprocess
import sys
from pathlib import Path

# Tables longer than this are cut in the report (the CSV file is linked in full).
MAX_TABLE_ROWS = 60
# Temperatures [degC] at which the Fig. 6 radius curves are summarized.
FIG6_TEMPERATURES_DEGC = (25, 50, 75, 100, 125, 150)

STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em auto; max-width: 1200px; color: #222; }
h1 { margin-bottom: 0.2em; }
table { border-collapse: collapse; margin: 0.6em 0 1.2em; font-size: 0.86em; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.pass { background: #d9f2d9; color: #145214; font-weight: bold; }
.fail { background: #f8d0d0; color: #8a1010; font-weight: bold; }
.verdict-pass { border-left: 8px solid #2e9b2e; padding-left: 0.6em; }
.verdict-fail { border-left: 8px solid #c62828; padding-left: 0.6em; }
img { max-width: 100%; border: 1px solid #ddd; margin: 4px 0; }
.shapes img { max-width: 48%; }
pre { background: #f7f7f7; padding: 0.6em; overflow-x: auto; font-size: 0.8em; max-height: 30em; }
.note { color: #666; font-size: 0.9em; }
"""


VOID_ELEMENTS = {"meta", "img", "br", "hr", "link", "input", "col", "source", "wbr"}


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
            self.errors.append(f"line {self.getpos()[0]}: </{tag}> does not close {self.stack[-1] if self.stack else 'anything'}")
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
    cpu = ""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    memory = ""
    try:
        for line in open("/proc/meminfo"):
            if line.startswith("MemTotal:"):
                memory = f"{int(line.split()[1]) / 1024 ** 2:.1f} GiB"
                break
    except (OSError, ValueError):
        pass
    os_name = platform.platform()
    try:
        for line in open("/etc/os-release"):
            if line.startswith("PRETTY_NAME="):
                os_name = line.split("=", 1)[1].strip().strip('"') + f" ({platform.release()})"
    except OSError:
        pass
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
    except ValueError:
        return False


def fmt_cell(text):
    """Numbers with many digits are shortened to 6 significant digits for reading."""
    if is_number(text) and len(text) > 10:
        return f"{float(text):.6g}"
    return text


def html_table(header, rows, numeric=True):
    out = ["<table>", "<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr>"]
    for row in rows:
        cells = []
        for v in row:
            cls = ' class="num"' if numeric and is_number(v) else ""
            cells.append(f"<td{cls}>{html.escape(fmt_cell(v))}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def md_table(header, rows):
    esc = lambda s: str(s).replace("|", "\\|").replace("\n", " ")  # noqa: E731
    lines = ["| " + " | ".join(esc(h) for h in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(esc(fmt_cell(v)) for v in row) + " |" for row in rows]
    return "\n".join(lines)


def csv_section(path, title, rel, columns=None):
    """A CSV file as a table (cut at MAX_TABLE_ROWS rows; only `columns` when given, those
    present): (html, markdown)."""
    rows = read_csv(path)
    if not rows:
        return "", ""
    header = [c for c in columns if c in rows[0]] if columns else list(rows[0].keys())
    shown = [[r.get(h, "") or "" for h in header] for r in rows[:MAX_TABLE_ROWS]]
    cut = (f'<p class="note">first {MAX_TABLE_ROWS} of {len(rows)} rows; full table: '
           f'<a href="{html.escape(rel)}">{html.escape(path.name)}</a></p>' if len(rows) > MAX_TABLE_ROWS else
           f'<p class="note">file: <a href="{html.escape(rel)}">{html.escape(path.name)}</a></p>')
    h = f"<h3>{html.escape(title)}</h3>\n{html_table(header, shown)}\n{cut}"
    m = f"#### {title}\n\n{md_table(header, shown)}\n"
    return h, m


def fig6_summary(path, rel):
    """fig6_radius.csv summarized: radius [mm] per manipulator and material at a few temperatures."""
    rows = read_csv(path)
    if not rows:
        return "", ""
    curves = {}
    for r in rows:
        key = (r["manipulator"], r["material"])
        t = float(r["temperature_degC"])
        radius = r.get("bending_radius_m", "")
        curves.setdefault(key, {})[round(t, 6)] = (f"{1e3 * float(radius):.2f}" if radius else "straight") \
            if r.get("converged", "1") == "1" else "not converged"
    header = ["manipulator", "material"] + [f"{t} degC" for t in FIG6_TEMPERATURES_DEGC]
    table = [[k[0], k[1]] + [v.get(float(t), "") for t in FIG6_TEMPERATURES_DEGC] for k, v in sorted(curves.items())]
    h = (f"<h3>Fig. 6: three-point inner-edge bending radius [mm] (summary)</h3>\n{html_table(header, table)}\n"
         f'<p class="note">{len(rows)} points; full table: <a href="{html.escape(rel)}">{path.name}</a></p>')
    m = f"#### Fig. 6 bending radius [mm] (summary)\n\n{md_table(header, table)}\n"
    return h, m


# Known tables: (file name, title[, columns shown]); fig6_radius.csv is summarized separately.
KNOWN_TABLES = [
    ("fig5_table.csv", "Fig. 5: TCA onset temperature and elongation at 160 degC"),
    ("table1_grasp.csv", "Table I: grasping (paper comparison)"),
    ("fig8_force.csv", "Fig. 8: force (paper comparison)"),
    ("crosscheck.csv", "Cross-check: Cosserat shooting vs beam FE"),
    ("convergence.csv", "Convergence: error vs discretization"),
    ("shapes_summary.csv", "Suite scenarios: tip, global equilibrium (relative imbalance), timing",
     ["scenario", "status", "iterations", "tip_x_m", "tip_y_m", "tip_z_m", "bending_radius_m", "load_scale_N",
      "force_imbalance_rel", "moment_imbalance_rel", "imbalance_8_steps", "imbalance_16_steps", "wall_time_s",
      "reason"]),
]


def program_list(out_dir, timing):
    names = [t["program"] for t in timing]
    for d in sorted(p for p in out_dir.iterdir() if p.is_dir()):
        if d.name not in names and (d / "gates.csv").exists() and not timing:
            names.append(d.name)
    return names


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
            gates.append((r.get("program", name), r.get("gate", ""), r.get("measured", ""), r.get("bound", ""),
                          r.get("passed", "0") == "1"))
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

    n_failed = sum(1 for g in gates if not g[4])
    ok = n_failed == 0 and not problems and bool(gates)
    machine = machine_info()
    generated = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    summary_items = [
        ("verdict", "PASS" if ok else "FAIL"),
        ("gates", f"{len(gates)} total, {len(gates) - n_failed} passed, {n_failed} failed"),
        ("programs", f"{len(programs)} ({len(problems)} program-level problems)"),
        ("commit", commit_info(root)),
        ("started", run.get("started_utc", "unknown")),
        ("report written", generated),
        ("total run time", f"{run['total_seconds']} s" if "total_seconds" in run else "unknown"),
        ("build time", f"{run['build_seconds']} s" if "build_seconds" in run else "unknown"),
        ("build", f"{run.get('build_dir', '?')} ({run.get('build_type', '?')}, {run.get('jobs', '?')} jobs)"),
    ] + [(k, v) for k, v in machine.items()]

    h = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
         "<title>tcasim validation report</title>", f"<style>{STYLE}</style>", "</head>", "<body>"]
    h.append(f'<h1 class="verdict-{"pass" if ok else "fail"}">tcasim validation report: '
             f'{"PASS" if ok else "FAIL"}</h1>')
    h.append('<p class="note">Written by scripts/make_report.py from the outputs of scripts/validate.sh. '
             "Pass/fail is decided by the C++ validation programs (the same gates ctest runs).</p>")
    h.append("<h2>Summary</h2>")
    h.append(html_table(["item", "value"], summary_items, numeric=False))
    if problems:
        h.append('<p class="fail">Program-level problems:</p><ul>' +
                 "".join(f"<li>{html.escape(p)}</li>" for p in problems) + "</ul>")

    failed_gates = [g for g in gates if not g[4]]
    if failed_gates:
        h.append("<h2>Failed gates</h2>")
        h.append("<table><tr><th>program</th><th>gate</th><th>measured</th><th>bound</th></tr>" + "".join(
            f"<tr><td>{html.escape(p)}</td><td>{html.escape(g)}</td><td>{html.escape(m)}</td><td>{html.escape(b)}</td></tr>"
            for p, g, m, b, _ in failed_gates) + "</table>")

    # Per-program times.
    time_rows = []
    for name in programs:
        t = timing_by_name.get(name, {})
        rows = per_program[name]
        nf = sum(1 for r in rows if r.get("passed") != "1")
        time_rows.append([name, t.get("seconds", "?"), t.get("plot_seconds", "") or "-", t.get("exit_code", "?"),
                          f"{len(rows) - nf}/{len(rows)}"])
    h.append("<h2>Programs and run times</h2>")
    h.append(html_table(["program", "run time [s]", "plot time [s]", "exit code", "gates passed"], time_rows))

    # Every gate.
    h.append("<h2>Gates</h2>")
    h.append("<table><tr><th>program</th><th>gate</th><th>measured</th><th>bound</th><th>verdict</th></tr>")
    for prog, gate, measured, bound, passed in gates:
        cls = "pass" if passed else "fail"
        h.append(f"<tr><td>{html.escape(prog)}</td><td>{html.escape(gate)}</td><td>{html.escape(measured)}</td>"
                 f'<td>{html.escape(bound)}</td><td class="{cls}">{"PASS" if passed else "FAIL"}</td></tr>')
    h.append("</table>")

    md = [f"# tcasim validation report: {'PASS' if ok else 'FAIL'}", "", md_table(["item", "value"], summary_items),
          ""]
    if problems:
        md += ["Program-level problems:", ""] + [f"- {p}" for p in problems] + [""]
    md += ["## Programs and run times", "",
           md_table(["program", "run time [s]", "plot time [s]", "exit code", "gates passed"], time_rows), "",
           "## Gates", "",
           md_table(["program", "gate", "measured", "bound", "verdict"],
                    [[p, g, m, b, "PASS" if ok_ else "**FAIL**"] for p, g, m, b, ok_ in gates]), ""]

    # One section per program: its plots, its known tables, its log.
    for name in programs:
        d = out_dir / name
        rows = per_program[name]
        nf = sum(1 for r in rows if r.get("passed") != "1")
        t = timing_by_name.get(name, {})
        h.append(f'<h2 id="{html.escape(name)}">{html.escape(name)}</h2>')
        h.append(f'<p>{len(rows)} gates, {nf} failed; run time {html.escape(t.get("seconds", "?"))} s; '
                 f'exit code {html.escape(t.get("exit_code", "?"))}</p>')
        md += [f"## {name}", "", f"{len(rows)} gates, {nf} failed; run time {t.get('seconds', '?')} s", ""]
        pngs = sorted(d.glob("*.png")) if d.is_dir() else []
        shapes = [p for p in pngs if p.name.endswith("_shape.png")]
        others = [p for p in pngs if p not in shapes]
        for p in others:
            rel = f"{name}/{p.name}"
            h.append(f'<figure><img src="{html.escape(rel)}" alt="{html.escape(p.name)}">'
                     f"<figcaption>{html.escape(p.name)}</figcaption></figure>")
            md += [f"![{p.name}]({rel})", ""]
        if shapes:
            h.append('<div class="shapes">' + "".join(
                f'<img src="{html.escape(name + "/" + p.name)}" alt="{html.escape(p.name)}">' for p in shapes) +
                "</div>")
            h.append(f'<p class="note">VTK PolyData for ParaView: {", ".join(html.escape(v.name) for v in sorted(d.glob("*.vtp")))}</p>')
            md += [f"![{p.name}]({name}/{p.name})" for p in shapes] + [""]
        for fname, title, *columns in KNOWN_TABLES:
            if (d / fname).exists():
                th, tm = csv_section(d / fname, title, f"{name}/{fname}", columns[0] if columns else None)
                h.append(th)
                md += [tm, ""]
        if (d / "fig6_radius.csv").exists():
            th, tm = fig6_summary(d / "fig6_radius.csv", f"{name}/fig6_radius.csv")
            h.append(th)
            md += [tm, ""]
        known = {entry[0] for entry in KNOWN_TABLES} | {"fig6_radius.csv", "gates.csv"}
        other = [p for p in (sorted(d.glob("*.csv")) if d.is_dir() else [])
                 if p.name not in known and not p.name.endswith("_shape.csv")]
        if other:
            h.append('<p class="note">Other data: ' + ", ".join(
                f'<a href="{html.escape(name + "/" + p.name)}">{html.escape(p.name)}</a>' for p in other) + "</p>")
        log = d / "log.txt"
        if log.exists():
            text = log.read_text(errors="replace")
            h.append(f"<details><summary>log ({len(text.splitlines())} lines, "
                     f'<a href="{html.escape(name)}/log.txt">log.txt</a>)</summary>'
                     f"<pre>{html.escape(text)}</pre></details>")
            md += [f"Log: [{name}/log.txt]({name}/log.txt)", ""]
    h += ["</body>", "</html>", ""]

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
