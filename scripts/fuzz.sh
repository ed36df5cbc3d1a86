#!/usr/bin/env bash
# Fuzzes tcasim's input readers (scenario, TCA and material files) with libFuzzer under
# ASan + UBSan for SECONDS seconds: fuzz/scenario_fuzzer.cpp, built with clang-14 in
# build-fuzz/ (-DTCASIM_BUILD_FUZZ=ON). Every rejection must be an InputError; a crash, a
# leak, a sanitizer report or another exception stops the run and leaves the input in
# build-fuzz/artifacts/. The corpus (build-fuzz/corpus) starts from the shipped scenario
# and material files and grows across runs. Installs clang-14 and libfuzzer-14-dev itself
# with its runtimes (Debian packages, through scripts/setup.sh, only if missing); not part
# of the default build or test run.
# Usage: scripts/fuzz.sh SECONDS [-- libFuzzer flags]
#   env: TCASIM_FUZZ_BUILD_DIR (default build-fuzz), TCASIM_JOBS (default 2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TCASIM_FUZZ_BUILD_DIR:-$root/build-fuzz}"
jobs="${TCASIM_JOBS:-2}"

usage() { echo "usage: scripts/fuzz.sh SECONDS [-- libFuzzer flags]" >&2; exit 2; }
[ $# -ge 1 ] || usage
seconds="$1"; shift
[[ "$seconds" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: SECONDS = '$seconds' must be a positive integer" >&2; exit 2; }
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --) shift; extra=("$@"); break ;;
    *) usage ;;
  esac
  shift
done

# libclang-rt-14-dev holds the sanitizer and libFuzzer runtimes that -fsanitize= links;
# libomp-14-dev is the OpenMP that the SUNDIALS CMake package requires of clang.
bash "$root/scripts/setup.sh" clang-14 libfuzzer-14-dev libclang-rt-14-dev libomp-14-dev

flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTCASIM_BUILD_FUZZ=ON -DTCASIM_BUILD_TESTS=OFF -DTCASIM_BUILD_BENCH=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" >/dev/null
cmake --build "$build" -j "$jobs" --target scenario_fuzzer

corpus="$build/corpus"
mkdir -p "$corpus" "$build/artifacts"
cp "$root"/validation/scenarios/*.json "$root"/data/materials/*.json "$corpus"/
# The fuzzer writes each input to a file: on tmpfs that is ~8x faster than on a disk /tmp.
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
echo "fuzz.sh: fuzzing for $seconds s (corpus $corpus)"
"$build/bin/scenario_fuzzer" -max_total_time="$seconds" -print_final_stats=1 -dict="$root/fuzz/json.dict" \
  -artifact_prefix="$build/artifacts/" "${extra[@]}" "$corpus"
