#!/usr/bin/env bash
# Configures and builds tcasim in other configurations than the default, each in its own build
# folder, and runs the default tests of each configuration that has them: a target or test
# that silently needs a switched-off part fails here.
#   no-validation, no-tests, no-bench, no-python: TCASIM_BUILD_<PART>=OFF, one at a time;
#   shared: -DBUILD_SHARED_LIBS=ON (the libraries as shared objects; its default tests include
#           package_install_and_consume, so the installed program, libraries and consumer
#           example must find each other without the build tree).
# Usage: scripts/check-build-options.sh [CONFIGURATION...]   (default: all of them)
# The build folders build-no-validation, ..., build-shared sit beside build/, at the same
# depth, so a compiler cache (ccache with CCACHE_BASEDIR) reuses build/'s objects (the shared
# configuration compiles position-independent code: mostly its own cache entries).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="${JOBS:-$(nproc)}"

declare -A flags=(
  [no-validation]=-DTCASIM_BUILD_VALIDATION=OFF
  [no-tests]=-DTCASIM_BUILD_TESTS=OFF
  [no-bench]=-DTCASIM_BUILD_BENCH=OFF
  [no-python]=-DTCASIM_BUILD_PYTHON=OFF
  [shared]=-DBUILD_SHARED_LIBS=ON
)
all=(no-validation no-tests no-bench no-python shared)
configurations=("$@")
((${#configurations[@]})) || configurations=("${all[@]}")
for config in "${configurations[@]}"; do
  if [[ -z "${flags[$config]+set}" ]]; then
    echo "check-build-options: unknown configuration '$config' (known: ${all[*]})" >&2
    exit 2
  fi
done

failed=()
for config in "${configurations[@]}"; do
  build="$root/build-$config"
  echo "=== $config: ${flags[$config]} ($build)"
  start=$SECONDS
  if ! cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${flags[$config]}" >/dev/null ||
     ! cmake --build "$build" -j "$jobs"; then
    failed+=("$config: build")
    echo "=== $config: build failed after $((SECONDS - start)) s"
    continue
  fi
  echo "=== $config: built in $((SECONDS - start)) s"
  if [[ "$config" != no-tests ]]; then
    tests_start=$SECONDS
    ctest --test-dir "$build" -LE slow -j "$jobs" --output-on-failure --timeout 600 ||
      failed+=("$config: tests")
    echo "=== $config: tests ran in $((SECONDS - tests_start)) s"
  fi
  echo "=== $config: $((SECONDS - start)) s in all"
done

if ((${#failed[@]})); then
  printf 'check-build-options: FAILED: %s\n' "${failed[@]}"
  exit 1
fi
echo "check-build-options: every configuration built (and passed its tests): ${configurations[*]}"
