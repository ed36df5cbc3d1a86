#pragma once
/// The C interface between the beam FE and its UMFPACK back end, the plugin
/// libtcasim_umfpack.so (umfpack_plugin.cpp). The plugin is loaded with dlopen at the first
/// use of LinearSolver::kUmfpack (umfpack_loader.cpp), so that UMFPACK and what it pulls in
/// (CHOLMOD, BLAS/LAPACK, OpenBLAS, gfortran, gomp, METIS: some 16000 relocations) cost
/// nothing to a program that never asks for it. Plain C types only: no exception and no
/// C++ object crosses it.

extern "C" {

/// Version of this interface; a plugin of another version is refused.
#define TCASIM_UMFPACK_PLUGIN_ABI 1
/// Name of the factory function the plugin exports.
#define TCASIM_UMFPACK_PLUGIN_FACTORY "tcasim_umfpack_plugin_v1"

/// The back end's functions. A factorization object holds the pattern analysis of the first
/// matrix it factorizes and is reused for matrices of the same pattern.
struct tcasim_umfpack_plugin {
  int abi_version;  ///< TCASIM_UMFPACK_PLUGIN_ABI of the plugin's build
  /// A new factorization object; null when it cannot be allocated.
  void* (*create)(void);
  /// Frees an object of create() (null: nothing).
  void (*destroy)(void* lu);
  /// Factorizes the n x n compressed-column matrix (outer: n + 1 column starts, inner: row
  /// indices, values: nnz entries), analysing its pattern on the first call. 1 on success,
  /// 0 when UMFPACK fails (singular, out of memory).
  int (*factorize)(void* lu, int n, int nnz, const int* outer, const int* inner,
                   const double* values);
  /// Solves A x = b (n entries each) with the last factorization: 1 on success, else 0.
  int (*solve)(void* lu, int n, const double* b, double* x);
};

/// The plugin's one exported symbol (TCASIM_UMFPACK_PLUGIN_FACTORY).
typedef const tcasim_umfpack_plugin* (*tcasim_umfpack_plugin_factory)(void);

}  // extern "C"
