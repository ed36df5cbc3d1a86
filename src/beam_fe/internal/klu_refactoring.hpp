#pragma once
/// KLU with the symbolic analysis done once and the numeric factorization redone with the
/// previous pivot order (klu_refactor) while it stays sound: the sparse LU of the static
/// Newton solver (solver.cpp) and of the dynamics (dynamics.cpp). <klu.h> stays in the .cpp.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace tcasim::beam_fe::internal {

/// One KLU factorization of matrices that share one sparsity pattern.
class KluRefactoring {
 public:
  KluRefactoring();
  KluRefactoring(const KluRefactoring&) = delete;
  KluRefactoring& operator=(const KluRefactoring&) = delete;
  ~KluRefactoring();
  /// Factorizes K (compressed, the same pattern on every call); false on failure. Refactorizes
  /// with the last pivot order while the reciprocal condition estimate stays within
  /// kRefactorRcondRatio of the last full factorization's, else pivots afresh.
  bool factorize(Eigen::SparseMatrix<double>& K);
  /// Solves K x = b in place (x holds b on entry) with the last factorization; false on failure.
  bool solve(Eigen::VectorXd& x);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tcasim::beam_fe::internal
