#!/usr/bin/env bash
# Builds tcasim with AddressSanitizer + UndefinedBehaviorSanitizer in its own folder
# (build-sanitize/, RelWithDebInfo, -fsanitize=address,undefined -fno-sanitize-recover=undefined)
# and runs the unit tests and the quick validation gates (labels `unit` and `validation`,
# without `slow`). Any sanitizer report fails the test that triggers it, so the script exits
# non-zero. Installs dependencies first (scripts/setup.sh). The sanitized build takes several
# times longer than scripts/test.sh: run it before merging, not in the inner loop.
# Usage: scripts/check-sanitizers.sh [extra ctest args]
#        env: TCASIM_SANITIZE_BUILD_DIR (default build-sanitize), TCASIM_JOBS (default 2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
jobs="${TCASIM_JOBS:-2}"

bash "$root/scripts/setup.sh"
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
start=$(date +%s)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTCASIM_BUILD_BENCH=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" >/dev/null
cmake --build "$build" -j "$jobs"
built=$(date +%s)
echo "check-sanitizers.sh: build took $((built - start)) s"
# Leaks are reported too; a UBSan finding stops the process (no recovery) with a stack.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
ctest --test-dir "$build" -L "unit|validation" -LE slow -j "$jobs" --output-on-failure --timeout 1800 "$@" || status=$?
# A test judged by its output (PASS_REGULAR_EXPRESSION) ignores its exit code: look for
# sanitizer reports in the whole log too.
if grep -qE "runtime error:|ERROR: AddressSanitizer|ERROR: LeakSanitizer" "$build/Testing/Temporary/LastTest.log"; then
  echo "check-sanitizers.sh: sanitizer reports in $build/Testing/Temporary/LastTest.log" >&2
  status=1
fi
echo "check-sanitizers.sh: tests took $(( $(date +%s) - built )) s"
exit "$status"
