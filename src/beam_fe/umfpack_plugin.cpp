// The UMFPACK back end of the beam FE as a loadable module (umfpack_plugin_abi.hpp): Eigen's
// UmfPackLU behind the plugin's C interface. Only the factory is exported.
#include <Eigen/SparseCore>
#include <Eigen/UmfPackSupport>
#include <new>

#include "beam_fe/internal/umfpack_plugin_abi.hpp"

namespace {

using SpMat = Eigen::SparseMatrix<double>;

/// One factorization: the pattern is analysed on the first call, as the solver did in-process.
struct Factorization {
  Eigen::UmfPackLU<SpMat> lu;
  bool analysed = false;
};

void* create() noexcept { return new (std::nothrow) Factorization(); }

void destroy(void* lu) noexcept { delete static_cast<Factorization*>(lu); }

int factorize(void* lu, int n, int nnz, const int* outer, const int* inner,
              const double* values) noexcept {
  try {
    auto& f = *static_cast<Factorization*>(lu);
    const Eigen::Map<const SpMat> K(n, n, nnz, outer, inner, values);
    if (!f.analysed) f.lu.analyzePattern(K);
    f.analysed = true;
    f.lu.factorize(K);
    return f.lu.info() == Eigen::Success ? 1 : 0;
  } catch (...) {  // std::bad_alloc from Eigen's copies
    return 0;
  }
}

int solve(void* lu, int n, const double* b, double* x) noexcept {
  try {
    auto& f = *static_cast<Factorization*>(lu);
    Eigen::Map<Eigen::VectorXd>(x, n) = f.lu.solve(Eigen::Map<const Eigen::VectorXd>(b, n));
    return f.lu.info() == Eigen::Success ? 1 : 0;
  } catch (...) {
    return 0;
  }
}

constexpr tcasim_umfpack_plugin kPlugin = {TCASIM_UMFPACK_PLUGIN_ABI, &create, &destroy, &factorize,
                                           &solve};

}  // namespace

extern "C" __attribute__((visibility("default"))) const tcasim_umfpack_plugin*
tcasim_umfpack_plugin_v1() {
  return &kPlugin;
}
