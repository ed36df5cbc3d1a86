# SuiteSparse 5.12 ships no CMake package on Debian: locate KLU, UMFPACK and their common
# dependencies by hand and wrap them in imported targets:
#   tcasim::klu      KLU and what it needs (AMD, COLAMD, BTF, SuiteSparse_config): the beam
#                    FE's default sparse LU, linked into the libraries;
#   tcasim::umfpack  UMFPACK with CHOLMOD and BLAS/LAPACK: only the UMFPACK plugin
#                    (libtcasim_umfpack.so, loaded at run time) links it.
# Sets TcasimSuiteSparse_KLU_FOUND and TcasimSuiteSparse_UMFPACK_FOUND. Used by the build
# (TcasimDependencies.cmake, which needs both) and by the installed package
# (tcasimConfig.cmake, which needs KLU only), so both link the same libraries.
find_path(SUITESPARSE_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
foreach(_tcasim_ss_lib umfpack klu cholmod amd colamd btf suitesparseconfig)
  string(TOUPPER ${_tcasim_ss_lib} _tcasim_ss_LIB)
  find_library(SUITESPARSE_${_tcasim_ss_LIB}_LIBRARY ${_tcasim_ss_lib})
endforeach()

set(TcasimSuiteSparse_KLU_FOUND FALSE)
if(SUITESPARSE_INCLUDE_DIR AND SUITESPARSE_KLU_LIBRARY AND SUITESPARSE_AMD_LIBRARY AND
   SUITESPARSE_COLAMD_LIBRARY AND SUITESPARSE_BTF_LIBRARY AND SUITESPARSE_SUITESPARSECONFIG_LIBRARY)
  set(TcasimSuiteSparse_KLU_FOUND TRUE)
  if(NOT TARGET tcasim::klu)
    add_library(tcasim::klu INTERFACE IMPORTED)
    set_target_properties(tcasim::klu PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SUITESPARSE_INCLUDE_DIR}"
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${SUITESPARSE_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${SUITESPARSE_KLU_LIBRARY};${SUITESPARSE_AMD_LIBRARY};${SUITESPARSE_COLAMD_LIBRARY};${SUITESPARSE_BTF_LIBRARY};${SUITESPARSE_SUITESPARSECONFIG_LIBRARY}")
  endif()
endif()

set(TcasimSuiteSparse_UMFPACK_FOUND FALSE)
if(TcasimSuiteSparse_KLU_FOUND AND SUITESPARSE_UMFPACK_LIBRARY AND SUITESPARSE_CHOLMOD_LIBRARY AND
   EXISTS "${SUITESPARSE_INCLUDE_DIR}/umfpack.h")
  set(TcasimSuiteSparse_UMFPACK_FOUND TRUE)
  if(NOT TARGET tcasim::umfpack)
    find_package(BLAS QUIET)
    find_package(LAPACK QUIET)
    add_library(tcasim::umfpack INTERFACE IMPORTED)
    set_target_properties(tcasim::umfpack PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SUITESPARSE_INCLUDE_DIR}"
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${SUITESPARSE_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${SUITESPARSE_UMFPACK_LIBRARY};${SUITESPARSE_CHOLMOD_LIBRARY};tcasim::klu;${LAPACK_LIBRARIES};${BLAS_LIBRARIES}")
  endif()
endif()
unset(_tcasim_ss_lib)
unset(_tcasim_ss_LIB)
