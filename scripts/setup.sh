#!/usr/bin/env bash
# Installs every dependency of tcasim from Debian packages (bookworm).
# Idempotent: when every package is already installed it only checks and exits.
# Usage: scripts/setup.sh [PACKAGE...]   (as root, or with sudo available)
#   PACKAGE: extra Debian packages a script alone needs (scripts/fuzz.sh passes clang-14
#   and libFuzzer), installed the same way; the build itself needs none of them.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev          # Eigen 3.4: dense and sparse algebra
  libsundials-dev        # SUNDIALS 6.4: CVODE (ODE integration)
  libsuitesparse-dev     # SuiteSparse 5.12: UMFPACK/KLU/CHOLMOD via Eigen
  libgtest-dev           # GoogleTest
  libbenchmark-dev       # Google Benchmark
  libcli11-dev           # CLI11: command-line flags
  libfmt-dev             # fmt: formatting
  nlohmann-json3-dev     # nlohmann-json: scenario and result files
  python3-numpy python3-matplotlib   # plots (used through /usr/bin/python3)
  python3-dev pybind11-dev python3-pybind11   # the tcasim Python module (python/)
  python3-pytest         # its tests (tests/python)
  python3-distributed    # Dask distributed: the design-study runner (tcasim.study)
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
# --no-install-recommends keeps the install to what the build needs; libsundials-dev
# still depends on MPI/PETSc/hypre headers, which Debian does not let us avoid.
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup: done"
