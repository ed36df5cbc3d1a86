# SuiteSparse 5.12 ships no CMake package on Debian: locate UMFPACK, KLU, CHOLMOD and their
# common dependencies by hand and wrap them in the imported target tcasim::suitesparse.
# Sets TcasimSuiteSparse_FOUND. Used by the build (TcasimDependencies.cmake) and by the
# installed package (tcasimConfig.cmake), so both link the same libraries.
find_path(SUITESPARSE_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
set(_tcasim_ss_libs)
set(_tcasim_ss_missing FALSE)
foreach(_tcasim_ss_lib umfpack klu cholmod amd colamd btf suitesparseconfig)
  string(TOUPPER ${_tcasim_ss_lib} _tcasim_ss_LIB)
  find_library(SUITESPARSE_${_tcasim_ss_LIB}_LIBRARY ${_tcasim_ss_lib})
  if(SUITESPARSE_${_tcasim_ss_LIB}_LIBRARY)
    list(APPEND _tcasim_ss_libs ${SUITESPARSE_${_tcasim_ss_LIB}_LIBRARY})
  else()
    set(_tcasim_ss_missing TRUE)
  endif()
endforeach()
set(TcasimSuiteSparse_FOUND FALSE)
if(SUITESPARSE_INCLUDE_DIR AND NOT _tcasim_ss_missing)
  set(TcasimSuiteSparse_FOUND TRUE)
  find_package(BLAS QUIET)
  find_package(LAPACK QUIET)
  if(NOT TARGET tcasim::suitesparse)
    add_library(tcasim::suitesparse INTERFACE IMPORTED)
    set_target_properties(tcasim::suitesparse PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SUITESPARSE_INCLUDE_DIR}"
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${SUITESPARSE_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${_tcasim_ss_libs};${LAPACK_LIBRARIES};${BLAS_LIBRARIES}")
  endif()
endif()
unset(_tcasim_ss_libs)
unset(_tcasim_ss_missing)
