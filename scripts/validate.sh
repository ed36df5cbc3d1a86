#!/usr/bin/env bash
# The main job: builds tcasim, runs every validation program in full on the shipped
# scenarios, makes the plots and writes the report OUT_DIR/report.html (and its Markdown
# twin report.md) with scripts/make_report.py. Exits non-zero if any gate fails, or any
# program or plot script fails.
# When Chromium is installed, the report is also rendered headless and checked (images,
# verdict in view, screenshot OUT_DIR/report-screenshot.png; scripts/check_report_browser.py).
# Usage: scripts/validate.sh [OUT_DIR]     (default: out/)
#        env: TCASIM_BUILD_DIR (default build), TCASIM_JOBS (default 2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_BUILD_DIR:-$root/build}"
out="$(mkdir -p "${1:-$root/out}" && cd "${1:-$root/out}" && pwd)"
jobs="${TCASIM_JOBS:-2}"
py=/usr/bin/python3   # Debian's interpreter: it has numpy and matplotlib

t0=$(date +%s)
# Seconds since a $EPOCHREALTIME stamp, to 0.01 s.
elapsed() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }'; }
started_utc=$(date -u +%Y-%m-%dT%H:%M:%SZ)
echo "[validate] 1/5 dependencies"
bash "$root/scripts/setup.sh"
echo "[validate] 2/5 build ($build)"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$jobs"
build_seconds=$(( $(date +%s) - t0 ))

# program name | plot script (empty when none) | extra arguments
programs=(
  "validate_fig5_tca|plot_fig5.py|--tcasim $build/bin/tcasim"
  "validate_fig6_radius|plot_fig6.py|"
  "validate_shapes|plot_shapes.py|"
  "validate_table1_grasp|plot_table1.py|"
  "validate_fig8_force|plot_fig8.py|"
  "validate_crosscheck|plot_crosscheck.py|"
  "validate_convergence|plot_convergence.py|"
  "validate_dynamics|plot_dynamics.py|"
  "validate_dynamic_crosscheck|plot_dynamic_crosscheck.py|"
  "validate_measured_tca|plot_measured_tca.py|"
  "validate_contact|plot_contact.py|"
)
echo "[validate] 3/5 validation programs -> $out"
failed=()
timing="$out/timing.csv"
echo "program,exit_code,seconds,plot_script,plot_exit_code,plot_seconds" > "$timing"
i=0
for entry in "${programs[@]}"; do
  i=$((i + 1))
  IFS='|' read -r name plot extra <<< "$entry"
  dir="$out/$name"
  rm -rf "$dir"; mkdir -p "$dir"   # no stale plots or gates from an earlier run
  echo "[validate]   ($i/${#programs[@]}) $name"
  start=$EPOCHREALTIME
  # The full output goes to the log; its step lines and failed gates are shown as progress.
  # shellcheck disable=SC2086  # extra holds separate arguments
  set +e
  "$build/validation/bin/$name" --out-dir "$dir" $extra 2>&1 | tee "$dir/log.txt" |
    grep --line-buffered -E '^Step|\[FAIL\]|: error:' | sed -u 's/^/[validate]       | /'
  rc=${PIPESTATUS[0]}
  set -e
  secs=$(elapsed "$start")
  if [ "$rc" -eq 0 ]; then status=PASS; else status="FAIL (exit code $rc)"; failed+=("$name"); fi
  echo "[validate]       $status in ${secs} s (log: $dir/log.txt)"
  plot_rc=""; plot_secs=""
  if [ -n "$plot" ]; then
    plot_start=$EPOCHREALTIME
    set +e
    "$py" "$root/scripts/$plot" "$dir" >> "$dir/log.txt" 2>&1
    plot_rc=$?
    set -e
    plot_secs=$(elapsed "$plot_start")
    if [ "$plot_rc" -ne 0 ]; then
      echo "[validate]       plot script $plot FAILED (exit code $plot_rc, see log)"; failed+=("$name:plot")
    else
      echo "[validate]       plot $plot in ${plot_secs} s"
    fi
  fi
  echo "$name,$rc,$secs,$plot,$plot_rc,$plot_secs" >> "$timing"
done

total_seconds=$(( $(date +%s) - t0 ))
{
  echo "key,value"
  echo "started_utc,$started_utc"
  echo "total_seconds,$total_seconds"
  echo "build_seconds,$build_seconds"
  echo "build_dir,$build"
  echo "build_type,Release"
  echo "jobs,$jobs"
} > "$out/run_info.csv"
echo "[validate] 4/5 report: $out/report.html"
set +e
"$py" "$root/scripts/make_report.py" "$out" --root "$root"
report_rc=$?
set -e
if [ "$report_rc" -eq 2 ]; then failed+=("make_report.py"); fi
if [ "$report_rc" -eq 1 ] && [ ${#failed[@]} -eq 0 ]; then failed+=("failed gates or programs without gates (see report)"); fi
# The page as a reader sees it (headless Chromium: images load, verdict in the first
# viewport, out/report-screenshot.png) when Chromium is installed; scripts/check_report.sh
# installs it and runs the same check.
if [ "$report_rc" -ne 2 ]; then
  set +e
  "$py" "$root/scripts/check_report_browser.py" "$out" | sed -u 's/^/[validate]   /'
  browser_rc=${PIPESTATUS[0]}
  set -e
  if [ "$browser_rc" -eq 1 ]; then failed+=("report rendering (check_report_browser.py)"); fi
fi

echo "[validate] 5/5 verdict"
if [ ${#failed[@]} -gt 0 ]; then
  echo "[validate] FAILED: ${failed[*]} (report: $out/report.html, ${total_seconds} s)"
  exit 1
fi
echo "[validate] all gates passed in ${total_seconds} s (report: $out/report.html)"
