// KLU with refactorization (beam_fe/internal/klu_refactoring.hpp).
#include "beam_fe/internal/klu_refactoring.hpp"

extern "C" {
#include <klu.h>
}

namespace tcasim::beam_fe::internal {
namespace {

/// Accept a refactorization (pivot order of the last full factorization) while the crude
/// reciprocal condition estimate min|U_kk|/max|U_kk| stays within this factor of the one
/// of that full factorization; below it a pivot has degraded and KLU pivots afresh.
constexpr double kRefactorRcondRatio = 1e-3;

}  // namespace

struct KluRefactoring::Impl {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  double rcond_full = 0.0;
};

KluRefactoring::KluRefactoring() : impl_(std::make_unique<Impl>()) { klu_defaults(&impl_->common); }

KluRefactoring::~KluRefactoring() {
  Impl& d = *impl_;
  if (d.numeric) klu_free_numeric(&d.numeric, &d.common);
  if (d.symbolic) klu_free_symbolic(&d.symbolic, &d.common);
}

bool KluRefactoring::factorize(Eigen::SparseMatrix<double>& K) {
  Impl& d = *impl_;
  int* Ap = K.outerIndexPtr();
  int* Ai = K.innerIndexPtr();
  double* Ax = K.valuePtr();
  const int n = static_cast<int>(K.rows());
  if (!d.symbolic) {
    d.symbolic = klu_analyze(n, Ap, Ai, &d.common);
    if (!d.symbolic) return false;
  }
  if (d.numeric) {
    if (klu_refactor(Ap, Ai, Ax, d.symbolic, d.numeric, &d.common) &&
        klu_rcond(d.symbolic, d.numeric, &d.common) &&
        d.common.rcond >= kRefactorRcondRatio * d.rcond_full) {
      return true;
    }
    klu_free_numeric(&d.numeric, &d.common);
  }
  d.numeric = klu_factor(Ap, Ai, Ax, d.symbolic, &d.common);
  if (!d.numeric || !klu_rcond(d.symbolic, d.numeric, &d.common)) return false;
  d.rcond_full = d.common.rcond;
  return d.common.status == KLU_OK;
}

bool KluRefactoring::solve(Eigen::VectorXd& x) {
  Impl& d = *impl_;
  return d.numeric &&
         klu_solve(d.symbolic, d.numeric, static_cast<int>(x.size()), 1, x.data(), &d.common) &&
         d.common.status == KLU_OK;
}

}  // namespace tcasim::beam_fe::internal
