#!/usr/bin/env bash
# Checks a validation report as a reader sees it: renders OUT_DIR/report.html (written by
# scripts/validate.sh) in headless Chromium at 1366 x 768, checks that every image loads,
# that the verdict is visible without scrolling, that the page does not scroll sideways and
# that the gate filter shows exactly the failures, and saves OUT_DIR/report-screenshot.png
# (scripts/check_report_browser.py). Installs Chromium (Debian package `chromium`) through
# scripts/setup.sh if it is missing; the build and the default tests do not need it.
# Usage: scripts/check_report.sh [OUT_DIR]     (default: out/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/out}"
bash "$root/scripts/setup.sh" chromium
exec /usr/bin/python3 "$root/scripts/check_report_browser.py" "$out"
