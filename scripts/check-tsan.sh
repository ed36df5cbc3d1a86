#!/usr/bin/env bash
# Thread safety of the parallel sweeps (`tcasim sweep --jobs N`, tcasim.sweep(jobs=N)): builds
# the thread pool's tests (common_tests: RunParallel.*) and the tcasim program with
# ThreadSanitizer in its own folder (build-tsan/, Release with -g -O1 -fsanitize=thread), then
# runs under TSan
#   1. the thread-pool tests and the ctest checks that parallel sweeps equal the serial run
#      (cli_sweep_*parallel*: both methods, several chunks on several threads), and
#   2. `tcasim sweep --jobs 2` of a shipped scenario with both methods.
# Any TSan report ("WARNING: ThreadSanitizer") fails the script. Only those targets are built
# (no Python module, benchmarks or validation programs), but the solver libraries are all
# compiled again: expect a build several times longer than one target of scripts/test.sh.
# Usage: scripts/check-tsan.sh [extra ctest args]
#        env: TCASIM_TSAN_BUILD_DIR (default build-tsan), TCASIM_JOBS (default 2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_TSAN_BUILD_DIR:-$root/build-tsan}"
jobs="${TCASIM_JOBS:-2}"

bash "$root/scripts/setup.sh"
flags="-fsanitize=thread -g -O1 -fno-omit-frame-pointer"
start=$(date +%s)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTCASIM_BUILD_BENCH=OFF \
  -DTCASIM_BUILD_VALIDATION=OFF -DTCASIM_BUILD_PYTHON=OFF \
  -DCMAKE_C_FLAGS_RELEASE="$flags" -DCMAKE_CXX_FLAGS_RELEASE="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" >/dev/null
cmake --build "$build" -j "$jobs" --target common_tests tcasim
built=$(date +%s)
echo "check-tsan.sh: build took $((built - start)) s"
# Keep going after a report (every race is listed), but exit non-zero at the end of a process
# that had one; second_deadlock_stack for lock-order reports.
export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=0:exitcode=66:second_deadlock_stack=1}"
log="$build/check-tsan.log"
: >"$log"
status=0
ctest --test-dir "$build" -R '^RunParallel\.|^cli_sweep_.*parallel' -j "$jobs" --output-on-failure \
  --timeout 1800 "$@" || status=$?
cat "$build/Testing/Temporary/LastTest.log" >>"$log"
tcasim="$build/bin/tcasim"
scenario="$root/validation/scenarios/circular-manipulator.json"
run() {  # a sweep on two threads; stderr (progress, TSan reports) into the log
  echo "check-tsan.sh: tcasim $*" | tee -a "$log"
  "$tcasim" "$@" --jobs 2 --chunk 3 --out "$build/check-tsan-sweep.csv" 2>>"$log" || status=$?
}
run sweep "$scenario" --actuator tca --temperatures-degC 25:80:5
run sweep "$scenario" --actuator tca --temperatures-degC 25:80:5 --method fe --elements 8
# A test judged by its output (PASS_REGULAR_EXPRESSION) ignores its exit code: look for
# reports in the whole log too.
if grep -q "WARNING: ThreadSanitizer" "$log"; then
  echo "check-tsan.sh: ThreadSanitizer reports in $log:" >&2
  grep -A3 "WARNING: ThreadSanitizer" "$log" | head -40 >&2
  status=1
fi
echo "check-tsan.sh: tests took $(( $(date +%s) - built )) s"
exit "$status"
