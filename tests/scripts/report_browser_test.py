"""Renders a report in headless Chromium (scripts/check_report_browser.py) and checks that the
check can fail: a report of the fixture passes (images load, verdict in the first 1366 x 768
viewport, no horizontal scrolling, the failures-only filter); the same report with a broken
image, or with the verdict pushed below the first viewport, fails saying so. The fixture, its report and the screenshot stay in OUT_DIR.
Usage: /usr/bin/python3 tests/scripts/report_browser_test.py OUT_DIR
Exit code 0 pass, 1 fail, 77 skipped (no Chromium)."""
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(HERE))
from report_fixture import make_fixture  # noqa: E402

SKIP = 77


def run(*args):
    p = subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True, timeout=300)
    print(p.stdout + p.stderr, end="")
    return p.returncode, p.stdout


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    out = Path(argv[1]).resolve()
    shutil.rmtree(out, ignore_errors=True)
    make_fixture(out, failing_gate=True)
    rc, _ = run(ROOT / "scripts" / "make_report.py", out)
    if rc != 1:  # the fixture has a failed gate
        print(f"report_browser_test: make_report.py exited {rc}, expected 1 (a failed gate)")
        return 1
    rc, text = run(ROOT / "scripts" / "check_report_browser.py", out)
    if rc == SKIP:
        return SKIP
    if rc != 0:
        print("report_browser_test: FAILED: the fixture's report does not pass the browser checks")
        return 1
    if not (out / "report-screenshot.png").is_file():
        print("report_browser_test: FAILED: no screenshot")
        return 1
    # The same page with one image that cannot be decoded must fail, naming the image.
    broken = out.parent / (out.name + "-broken-image")
    shutil.rmtree(broken, ignore_errors=True)
    shutil.copytree(out, broken)
    (broken / "validate_shapes" / "b_shape.png").write_bytes(b"not a png")
    rc, text = run(ROOT / "scripts" / "check_report_browser.py", broken)
    if rc != 1 or "validate_shapes/b_shape.png did not load" not in text:
        print(f"report_browser_test: FAILED: a broken image gave exit code {rc} without naming it")
        return 1
    # A verdict pushed below the first viewport must fail too.
    low = out.parent / (out.name + "-low-verdict")
    shutil.rmtree(low, ignore_errors=True)
    shutil.copytree(out, low)
    page = (low / "report.html").read_text()
    (low / "report.html").write_text(page.replace("<body>", '<body>\n<div style="height: 900px"></div>', 1))
    rc, text = run(ROOT / "scripts" / "check_report_browser.py", low)
    if rc != 1 or "the verdict is not within the first 1366 x 768 viewport" not in text:
        print(f"report_browser_test: FAILED: a verdict below the fold gave exit code {rc} without saying so")
        return 1
    print("report_browser_test: passed (and a broken image and a verdict below the fold are caught)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
