#pragma once
/// Helpers shared by the FE dynamics' translation units (dynamics.cpp, dynamics_damping.cpp):
/// shape functions, Gauss rules, slots of a sparse pattern, KLU with refactorization.
#include <Eigen/SparseCore>
#include <algorithm>
#include <stdexcept>
#include <vector>

extern "C" {
#include <klu.h>
}

namespace tcasim::beam_fe::dynamics_internal {

using SpMat = Eigen::SparseMatrix<double>;

/// Lagrange shape functions on xi in [-1, 1] (equally spaced nodes) and their xi-derivatives.
inline void shape(int order, double xi, double* N, double* dN) {
  if (order == 1) {
    N[0] = 0.5 * (1.0 - xi);
    N[1] = 0.5 * (1.0 + xi);
    dN[0] = -0.5;
    dN[1] = 0.5;
  } else {
    N[0] = 0.5 * xi * (xi - 1.0);
    N[1] = 1.0 - xi * xi;
    N[2] = 0.5 * xi * (xi + 1.0);
    dN[0] = xi - 0.5;
    dN[1] = -2.0 * xi;
    dN[2] = xi + 0.5;
  }
}

/// Gauss-Legendre rule with `points` points on [-1, 1].
inline void gauss_rule(int points, std::vector<double>& xi, std::vector<double>& w) {
  if (points == 1) {
    xi = {0.0};
    w = {2.0};
  } else if (points == 2) {
    const double x = 1.0 / std::sqrt(3.0);
    xi = {-x, x};
    w = {1.0, 1.0};
  } else {
    const double x = std::sqrt(0.6);
    xi = {-x, 0.0, x};
    w = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  }
}

/// Index of entry (i, j) of a compressed column-major matrix in its values (it must exist).
inline int slot_of(const SpMat& A, int i, int j) {
  const int* inner = A.innerIndexPtr();
  const int* begin = inner + A.outerIndexPtr()[j];
  const int* end = inner + A.outerIndexPtr()[j + 1];
  const int* it = std::lower_bound(begin, end, i);
  if (it == end || *it != i) throw std::logic_error("beam_fe dynamics: entry outside the pattern");
  return static_cast<int>(it - inner);
}

/// KLU with the symbolic analysis done once and refactorization with the last pivot order
/// while its reciprocal condition estimate stays within 1e-3 of the last full factorization's.
class Klu {
 public:
  Klu() { klu_defaults(&common_); }
  Klu(const Klu&) = delete;
  Klu& operator=(const Klu&) = delete;
  ~Klu() {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }
  bool factorize(SpMat& A) {
    int* Ap = A.outerIndexPtr();
    int* Ai = A.innerIndexPtr();
    double* Ax = A.valuePtr();
    if (!symbolic_) symbolic_ = klu_analyze(static_cast<int>(A.rows()), Ap, Ai, &common_);
    if (!symbolic_) return false;
    if (numeric_) {
      if (klu_refactor(Ap, Ai, Ax, symbolic_, numeric_, &common_) &&
          klu_rcond(symbolic_, numeric_, &common_) && common_.rcond >= 1e-3 * rcond_full_) {
        return true;
      }
      klu_free_numeric(&numeric_, &common_);
    }
    numeric_ = klu_factor(Ap, Ai, Ax, symbolic_, &common_);
    if (!numeric_ || !klu_rcond(symbolic_, numeric_, &common_)) return false;
    rcond_full_ = common_.rcond;
    return common_.status == KLU_OK;
  }
  bool solve(Eigen::VectorXd& x) {
    return numeric_ &&
           klu_solve(symbolic_, numeric_, static_cast<int>(x.size()), 1, x.data(), &common_) &&
           common_.status == KLU_OK;
  }

 private:
  klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  double rcond_full_ = 0.0;
};

}  // namespace tcasim::beam_fe::dynamics_internal
