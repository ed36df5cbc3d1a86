#!/usr/bin/python3
"""Renders a validation report in headless Chromium and checks what a reader sees.

Usage: /usr/bin/python3 scripts/check_report_browser.py OUT_DIR [--chromium PATH]

Loads OUT_DIR/report.html (scripts/make_report.py) at a laptop's 1366 x 768 viewport and
checks, from inside the page:
  - every <img> loaded (complete, naturalWidth > 0) and has a non-empty alt text;
  - the verdict (#verdict) lies within the first viewport, without scrolling;
  - the page does not scroll horizontally (document width <= viewport width);
  - the gate filter works: with "failures only" checked, exactly the failed gates show.
The checks run in a small script injected into a copy of the page (OUT_DIR/.report-check.html,
removed afterwards); it writes its findings into the DOM, which Chromium's --dump-dom prints.
A screenshot of the first viewport goes to OUT_DIR/report-screenshot.png.

Exit code 0 when every check passes, 1 when one fails, 77 (skipped, as ctest's
SKIP_RETURN_CODE) when no Chromium is installed (Debian package `chromium`; scripts/check_report.sh
installs it). Standard library only.
"""
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

WIDTH, HEIGHT = 1366, 768
SKIP = 77

# Runs after the page's own scripts and every image (window load); writes a JSON verdict.
CHECK_SCRIPT = """
<script>
window.addEventListener('load', function () {
  var out = {images: [], verdict: null, scroll_width: 0, viewport: [window.innerWidth, window.innerHeight],
             filter: null};
  document.querySelectorAll('img').forEach(function (img) {
    out.images.push({src: img.getAttribute('src'), alt: img.getAttribute('alt') || '',
                     loaded: img.complete && img.naturalWidth > 0, width: img.naturalWidth});
  });
  var v = document.getElementById('verdict');
  if (v) {
    var r = v.getBoundingClientRect();
    out.verdict = {top: r.top, bottom: r.bottom, left: r.left, right: r.right,
                   visible: getComputedStyle(v).visibility !== 'hidden' && r.height > 0,
                   text: v.textContent.trim().slice(0, 200)};
  }
  out.scroll_width = document.documentElement.scrollWidth;
  var only = document.getElementById('gate-only-failed');
  if (only) {
    var details = only.closest('details');
    if (details) details.open = true;
    var before = only.checked;
    only.checked = true;
    only.dispatchEvent(new Event('change'));
    var rows = document.querySelectorAll('#gate-table tr.gate');
    var shown = 0, failed = 0, shown_passed = 0;
    rows.forEach(function (tr) {
      var isFailed = tr.classList.contains('failed');
      if (isFailed) failed++;
      if (!tr.hidden) { shown++; if (!isFailed) shown_passed++; }
    });
    only.checked = false;
    only.dispatchEvent(new Event('change'));
    var all_shown = 0;
    rows.forEach(function (tr) { if (!tr.hidden) all_shown++; });
    only.checked = before;
    only.dispatchEvent(new Event('change'));
    out.filter = {rows: rows.length, failed: failed, shown_failures_only: shown, shown_passed: shown_passed,
                  shown_all: all_shown};
  }
  var pre = document.createElement('pre');
  pre.id = 'report-check-result';
  // The markers are built here so the script's own text never matches them.
  pre.textContent = ['REPORT', 'CHECK', 'BEGIN'].join('-') + JSON.stringify(out) +
                    ['REPORT', 'CHECK', 'END'].join('-');
  document.body.appendChild(pre);
});
</script>
"""


def find_chromium(explicit):
    for name in ([explicit] if explicit else []) + ["chromium", "chromium-browser", "google-chrome"]:
        path = shutil.which(name) if name else None
        if path:
            return path
    return None


def run_chromium(chromium, args, timeout=120):
    # A profile of our own: no interference with (or from) another Chromium on the machine.
    with tempfile.TemporaryDirectory(prefix="report-check-profile-") as profile:
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
               "--no-first-run", "--allow-file-access-from-files", f"--user-data-dir={profile}",
               f"--window-size={WIDTH},{HEIGHT}"] + args
        return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)


def main(argv):
    args = argv[1:]
    chromium_arg = None
    if "--chromium" in args:
        i = args.index("--chromium")
        chromium_arg = args[i + 1]
        del args[i:i + 2]
    if len(args) != 1:
        print(__doc__)
        return 2
    out_dir = Path(args[0]).resolve()
    report = out_dir / "report.html"
    if not report.is_file():
        print(f"check_report_browser: {report} does not exist (run scripts/make_report.py first)")
        return 1
    chromium = find_chromium(chromium_arg)
    if not chromium:
        print("check_report_browser: SKIPPED: no Chromium found (Debian package `chromium`; "
              "scripts/check_report.sh installs it)")
        return SKIP

    # The copy sits beside the report so its relative image links resolve the same way.
    probe = out_dir / ".report-check.html"
    text = report.read_text()
    probe.write_text(text.replace("</body>", CHECK_SCRIPT + "</body>", 1))
    try:
        dom = run_chromium(chromium, ["--virtual-time-budget=10000", "--dump-dom", probe.as_uri()])
    finally:
        probe.unlink(missing_ok=True)
    m = re.search(r"REPORT-CHECK-BEGIN(.*?)REPORT-CHECK-END", html.unescape(dom.stdout), re.S)
    if not m:
        print(f"check_report_browser: FAILED: the page's check did not run (chromium exit code {dom.returncode})\n"
              f"{dom.stderr[-2000:]}")
        return 1
    found = json.loads(m.group(1))

    screenshot = out_dir / "report-screenshot.png"
    shot = run_chromium(chromium, ["--virtual-time-budget=5000", f"--screenshot={screenshot}", report.as_uri()])

    problems = []
    images = found["images"]
    if not images:
        problems.append("the page has no images")
    for img in images:
        if not img["loaded"]:
            problems.append(f"image {img['src']} did not load")
        if not img["alt"].strip():
            problems.append(f"image {img['src']} has no alt text")
    v = found["verdict"]
    if not v:
        problems.append("no element #verdict")
    else:
        inside = v["visible"] and v["top"] >= 0 and v["bottom"] <= HEIGHT and v["left"] >= 0 and v["right"] <= WIDTH
        if not inside:
            problems.append(f"the verdict is not within the first {WIDTH} x {HEIGHT} viewport: box {v}")
    if found["scroll_width"] > found["viewport"][0]:
        problems.append(f"the page scrolls horizontally: {found['scroll_width']} px wide in a "
                        f"{found['viewport'][0]} px viewport")
    f = found["filter"]
    if not f:
        problems.append("no gate filter (#gate-only-failed)")
    else:
        if f["shown_failures_only"] != f["failed"] or f["shown_passed"] != 0:
            problems.append(f"'failures only' shows {f['shown_failures_only']} rows ({f['shown_passed']} passed "
                            f"ones) for {f['failed']} failed gates")
        if f["shown_all"] != f["rows"]:
            problems.append(f"without the filter {f['shown_all']} of {f['rows']} gate rows show")
    if shot.returncode != 0 or not screenshot.is_file() or screenshot.stat().st_size == 0:
        problems.append(f"no screenshot written (chromium exit code {shot.returncode})")

    print(f"check_report_browser: {report}: {len(images)} images "
          f"({sum(1 for i in images if i['loaded'])} loaded), verdict box "
          f"{'top %.0f..%.0f px' % (v['top'], v['bottom']) if v else 'missing'} of {HEIGHT}, "
          f"page width {found['scroll_width']} px of {found['viewport'][0]}, "
          f"gate filter {f['shown_failures_only'] if f else '?'} of {f['rows'] if f else '?'} rows for failures; "
          f"screenshot {screenshot}")
    if problems:
        print("check_report_browser: FAILED:\n  " + "\n  ".join(problems[:30]))
        return 1
    print("check_report_browser: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
