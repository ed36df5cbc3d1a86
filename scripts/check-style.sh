#!/usr/bin/env bash
# House style checks (not part of the default build or test run):
#  1. clang-format (the repository's .clang-format): every tracked C++ file must be formatted;
#     with --fix the files are formatted in place instead.
#  2. clang-tidy (the repository's .clang-tidy: a handful of bug-prone and performance checks)
#     on the library, command-line and Python-module sources; any finding fails.
# Installs clang-format and clang-tidy (Debian packages) if missing, configures build/ with
# compile_commands.json. Usage: scripts/check-style.sh [--fix] [--format-only]
#   env: TCASIM_BUILD_DIR (default build), TCASIM_JOBS (default 2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_BUILD_DIR:-$root/build}"
jobs="${TCASIM_JOBS:-2}"
fix=0
tidy=1
for arg in "$@"; do
  case "$arg" in
    --fix) fix=1 ;;
    --format-only) tidy=0 ;;
    *) echo "check-style: unknown argument '$arg' (use --fix, --format-only)" >&2; exit 2 ;;
  esac
done

bash "$root/scripts/setup.sh" clang-format clang-tidy
cd "$root"
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if [ "$fix" -eq 1 ]; then
  clang-format -i "${files[@]}"
  echo "check-style: formatted ${#files[@]} files"
elif ! clang-format --dry-run --Werror "${files[@]}"; then
  echo "check-style: FAIL: files above are not clang-formatted (scripts/check-style.sh --fix)" >&2
  exit 1
else
  echo "check-style: clang-format clean (${#files[@]} files)"
fi

[ "$tidy" -eq 1 ] || exit 0
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > /dev/null
# Generated sources and headers must exist before clang-tidy reads the compile commands.
cmake --build "$build" -j "$jobs" > /dev/null
mapfile -t sources < <(git ls-files 'src/*.cpp' 'apps/*.cpp' 'python/src/*.cpp')
log="$build/check-style-tidy.log"
if ! printf '%s\n' "${sources[@]}" |
    xargs -P "$jobs" -n 4 clang-tidy -p "$build" --quiet > "$log" 2>&1; then
  grep -E "(warning|error):" "$log" >&2 || cat "$log" >&2
  echo "check-style: FAIL: clang-tidy findings (full log: $log)" >&2
  exit 1
fi
echo "check-style: clang-tidy clean (${#sources[@]} files)"
