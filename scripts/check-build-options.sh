#!/usr/bin/env bash
# Configures and builds tcasim with each optional part switched off in turn
# (TCASIM_BUILD_VALIDATION, TCASIM_BUILD_TESTS, TCASIM_BUILD_BENCH, TCASIM_BUILD_PYTHON), each in its own build
# folder, and runs the default tests of each configuration that has them: a target or test
# that silently needs a switched-off part fails here.
# Usage: scripts/check-build-options.sh
# The build folders build-no-validation, build-no-tests, build-no-bench, build-no-python sit beside build/, at
# the same depth, so a compiler cache (ccache with CCACHE_BASEDIR) reuses build/'s objects.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="${JOBS:-$(nproc)}"

failed=()
for option in TCASIM_BUILD_VALIDATION TCASIM_BUILD_TESTS TCASIM_BUILD_BENCH TCASIM_BUILD_PYTHON; do
  part="${option#TCASIM_BUILD_}"
  build="$root/build-no-${part,,}"
  echo "=== $option=OFF ($build)"
  if ! cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "-D$option=OFF" >/dev/null ||
     ! cmake --build "$build" -j "$jobs"; then
    failed+=("$option=OFF: build")
    continue
  fi
  if [[ "$option" != TCASIM_BUILD_TESTS ]]; then
    ctest --test-dir "$build" -LE slow -j "$jobs" --output-on-failure --timeout 600 ||
      failed+=("$option=OFF: tests")
  fi
done

if ((${#failed[@]})); then
  printf 'check-build-options: FAILED: %s\n' "${failed[@]}"
  exit 1
fi
echo "check-build-options: every configuration built (and passed its tests)"
