#!/usr/bin/env bash
# The main job: builds tcasim, runs every validation program in full on the shipped
# scenarios, makes the plots and writes a summary. Exits non-zero if any gate fails.
# Usage: scripts/validate.sh [OUT_DIR]     (default: out/)
#        env: TCASIM_BUILD_DIR (default build), TCASIM_JOBS (default 2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_BUILD_DIR:-$root/build}"
out="$(mkdir -p "${1:-$root/out}" && cd "${1:-$root/out}" && pwd)"
jobs="${TCASIM_JOBS:-2}"
py=/usr/bin/python3   # Debian's interpreter: it has numpy and matplotlib

t0=$(date +%s)
echo "[validate] 1/4 dependencies"
bash "$root/scripts/setup.sh"
echo "[validate] 2/4 build ($build)"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$jobs"

# program name | plot script (empty when none) | extra arguments
programs=(
  "validate_fig5_tca|plot_fig5.py|--tcasim $build/bin/tcasim"
  "validate_fig6_radius|plot_fig6.py|"
)
echo "[validate] 3/4 validation programs -> $out"
failed=()
summary="$out/summary.md"
{
  echo "# tcasim validation summary"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "- machine: $(uname -srm), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "- commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo
} > "$summary"
i=0
for entry in "${programs[@]}"; do
  i=$((i + 1))
  IFS='|' read -r name plot extra <<< "$entry"
  dir="$out/$name"; mkdir -p "$dir"
  echo "[validate]   ($i/${#programs[@]}) $name"
  start=$(date +%s)
  # shellcheck disable=SC2086  # extra holds separate arguments
  if "$build/validation/bin/$name" --out-dir "$dir" $extra > "$dir/log.txt" 2>&1; then
    status=PASS
  else
    status=FAIL; failed+=("$name")
  fi
  secs=$(( $(date +%s) - start ))
  echo "[validate]       $status in ${secs} s (log: $dir/log.txt)"
  if [ -n "$plot" ]; then
    if ! "$py" "$root/scripts/$plot" "$dir" >> "$dir/log.txt" 2>&1; then
      echo "[validate]       plot script $plot failed (see log)"; failed+=("$name:plot")
    fi
  fi
  {
    echo "## $name: $status (${secs} s)"
    echo
    echo '```'
    cat "$dir/log.txt"
    echo '```'
    for png in "$dir"/*.png; do [ -e "$png" ] && echo "![$(basename "$png")]($name/$(basename "$png"))"; done
    echo
  } >> "$summary"
done

echo "[validate] 4/4 summary: $summary"
echo "- total run time: $(( $(date +%s) - t0 )) s" >> "$summary"
if [ ${#failed[@]} -gt 0 ]; then
  echo "[validate] FAILED: ${failed[*]}"
  exit 1
fi
echo "[validate] all gates passed in $(( $(date +%s) - t0 )) s"
