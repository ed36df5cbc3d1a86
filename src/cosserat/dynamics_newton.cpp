// Rod dynamics: the Newton (chord) iterations of one solve, with fresh Jacobians when the
// old factorization contracts too slowly and step halving after a fresh one.
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "cosserat/dynamics_impl.hpp"

namespace tcasim::cosserat {

using namespace dynamics_names;

DynamicsSummary RodDynamics::Impl::solve(Eigen::VectorXd& zz) {
  DynamicsSummary sum;
  const int n = unknowns();
  const Eigen::VectorXd unknown_scale = unknown_scales();
  Eigen::VectorXd r(n), z_old = zz, dz = Eigen::VectorXd::Zero(n);
  double rn_old = HUGE_VAL, lambda = 1.0;
  bool need_fresh = !lu_valid || lu_c0 != c0_active;
  bool step_taken = false, step_from_fresh = false;
  int stale_iterations = 0;
  for (int it = 0;; ++it) {
    const bool fresh = need_fresh;
    const bool ok = evaluate(zz, r, fresh);
    if (fresh) {
      ++sum.jacobians;
      need_fresh = false;
      if (!lu_valid) {
        sum.status = DynamicsSummary::Status::kSingularJacobian;
        sum.message = "SparseLU could not factorize the multiple-shooting Jacobian";
        return sum;
      }
    }
    const double rn = ok ? r.lpNorm<Eigen::Infinity>() : HUGE_VAL;
    sum.residual = rn;
    if (ok && rn <= opt.tolerance) {
      sum.status = DynamicsSummary::Status::kConverged;
      return sum;
    }
    if (!step_taken && !ok) {
      sum.status = DynamicsSummary::Status::kNonFinite;
      sum.message = "the state or a section's constitutive solve failed at the starting point";
      return sum;
    }
    if (sum.iterations >= opt.max_iterations) {
      sum.status = DynamicsSummary::Status::kMaxIterations;
      sum.message = "no convergence in " + std::to_string(opt.max_iterations) +
                    " iterations (scaled residual " + format_value(rn) + ")";
      return sum;
    }
    // A stale factorization gets kStaleIterations chord iterations, each of which must halve
    // the residual; then a fresh Jacobian at the last accepted point.
    if (step_taken && !step_from_fresh && stale_iterations >= kStaleIterations) {
      need_fresh = true;
      stale_iterations = 0;
      continue;  // re-evaluates at zz with a fresh Jacobian
    }
    if (step_taken && !(rn < (step_from_fresh ? 1.0 : 0.5) * rn_old)) {
      if (!step_from_fresh) {
        // The old factorization contracts too slowly here: a fresh Jacobian at z_old.
        zz = z_old;
        need_fresh = true;
        step_taken = false;
        rn_old = HUGE_VAL;
        continue;
      }
      if (lambda > 1.0 / 64.0) {
        lambda *= 0.5;
        zz = z_old + lambda * dz;
        continue;
      }
      sum.status = DynamicsSummary::Status::kNotConverging;
      sum.message = "a fresh Jacobian and 6 halvings of its step gave no decrease of the residual";
      return sum;
    }
    // Accept zz; next Newton step with the current factorization.
    z_old = zz;
    rn_old = rn;
    Eigen::VectorXd u =
        dense ? Eigen::VectorXd(dense_lu_.solve(-r)) : Eigen::VectorXd(lu_.solve(-r));
    if (!u.allFinite()) {
      sum.status = DynamicsSummary::Status::kSingularJacobian;
      sum.message = "the Newton step is not finite";
      return sum;
    }
    dz = u.cwiseProduct(unknown_scale);
    lambda = 1.0;
    zz = z_old + dz;
    step_taken = true;
    step_from_fresh = fresh;
    if (!fresh) ++stale_iterations;
    ++sum.iterations;
  }
}

}  // namespace tcasim::cosserat
