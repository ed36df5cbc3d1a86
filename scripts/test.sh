#!/usr/bin/env bash
# Builds tcasim and runs the default test set: unit tests and the quick validation
# gates (everything not labelled `slow`). Installs dependencies first (idempotent).
# Usage: scripts/test.sh [extra ctest args]     env: TCASIM_BUILD_DIR (default build)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_BUILD_DIR:-$root/build}"
jobs="${TCASIM_JOBS:-2}"

bash "$root/scripts/setup.sh"
start=$(date +%s)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j "$jobs"
built=$(date +%s)
echo "test.sh: build took $((built - start)) s"
ctest --test-dir "$build" -LE slow -j "$jobs" --output-on-failure --timeout 600 "$@"
echo "test.sh: tests took $(( $(date +%s) - built )) s"
