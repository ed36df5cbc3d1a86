#!/usr/bin/env bash
# Builds tcasim with AddressSanitizer + UndefinedBehaviorSanitizer in its own folder
# (build-sanitize/, RelWithDebInfo, -fsanitize=address,undefined -fno-sanitize-recover=undefined)
# and runs the unit tests and the quick validation gates (labels `unit` and `validation`,
# without `slow`; the Python tests with the sanitizer runtimes preloaded and leak checks off).
# Any sanitizer report fails the test that triggers it, so the script exits non-zero. Installs dependencies first (scripts/setup.sh). The sanitized build takes several
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
log="$build/Testing/Temporary/LastTest.log"
# A test judged by its output (PASS_REGULAR_EXPRESSION) ignores its exit code: look for
# sanitizer reports in the whole log too (after each ctest run: the next one rewrites it).
check_log() {
  if grep -qE "runtime error:|ERROR: AddressSanitizer|ERROR: LeakSanitizer" "$log"; then
    echo "check-sanitizers.sh: sanitizer reports in $log ($1)" >&2
    cp "$log" "$build/Testing/Temporary/sanitizer-$1.log"
    status=1
  fi
}
ctest --test-dir "$build" -L "unit|validation" -LE "slow|python" -j "$jobs" --output-on-failure \
  --timeout 1800 "$@" || status=$?
check_log cpp
# The Python tests load the sanitized extension into Debian's interpreter, which is not
# sanitized: the ASan and UBSan runtimes must be preloaded, and leak checking is off (the
# interpreter keeps objects alive at exit by design; the C++ under it is leak-checked above).
if [[ -n "$(ctest --test-dir "$build" -N -L python | grep -E '^ *Test +#')" ]]; then
  preload="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)"
  LD_PRELOAD="$preload" ASAN_OPTIONS="detect_leaks=0:abort_on_error=1" \
    ctest --test-dir "$build" -L python -LE slow -j "$jobs" --output-on-failure --timeout 1800 \
    "$@" || status=$?
  check_log python
fi
echo "check-sanitizers.sh: tests took $(( $(date +%s) - built )) s"
exit "$status"
