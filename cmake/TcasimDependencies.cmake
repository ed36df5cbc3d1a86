# Every dependency comes from a Debian package installed by scripts/setup.sh.
# A missing one stops configuration with the package to install.

macro(tcasim_require found what debian_package)
  if(NOT ${found})
    message(FATAL_ERROR "tcasim: ${what} not found. Install the Debian package "
                        "'${debian_package}' (scripts/setup.sh installs every dependency).")
  endif()
endmacro()

find_package(Eigen3 3.4 QUIET NO_MODULE)
tcasim_require(Eigen3_FOUND "Eigen 3.4" libeigen3-dev)

find_package(fmt QUIET)
tcasim_require(fmt_FOUND "fmt" libfmt-dev)

find_package(nlohmann_json 3.10 QUIET)
tcasim_require(nlohmann_json_FOUND "nlohmann-json" nlohmann-json3-dev)

find_package(CLI11 QUIET)
tcasim_require(CLI11_FOUND "CLI11" libcli11-dev)

find_package(SUNDIALS 6.4 QUIET)
tcasim_require(SUNDIALS_FOUND "SUNDIALS 6.4" libsundials-dev)

# std::thread (parallel sweeps, common/parallel.hpp): the C library's threads.
find_package(Threads REQUIRED)

include(TcasimSuiteSparse)
tcasim_require(TcasimSuiteSparse_KLU_FOUND "SuiteSparse (KLU)" libsuitesparse-dev)
tcasim_require(TcasimSuiteSparse_UMFPACK_FOUND "SuiteSparse (UMFPACK, CHOLMOD)" libsuitesparse-dev)

if(TCASIM_BUILD_TESTS)
  find_package(GTest QUIET)
  tcasim_require(GTest_FOUND "GoogleTest" libgtest-dev)
  include(GoogleTest)
endif()
if(TCASIM_BUILD_BENCH)
  find_package(benchmark QUIET)
  tcasim_require(benchmark_FOUND "Google Benchmark" libbenchmark-dev)
endif()

# Plots use Debian's interpreter explicitly: the first python3 on PATH may be another
# interpreter without numpy/matplotlib.
set(TCASIM_PYTHON "/usr/bin/python3" CACHE FILEPATH "Python with numpy and matplotlib (Debian's)")
if(NOT EXISTS "${TCASIM_PYTHON}")
  message(WARNING "tcasim: ${TCASIM_PYTHON} not found; plots will be skipped "
                  "(install python3-numpy and python3-matplotlib)")
endif()
