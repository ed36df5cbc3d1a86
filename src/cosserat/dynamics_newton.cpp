// Rod dynamics: the Newton (chord) iterations of one solve, with fresh Jacobians when the
// old factorization contracts too slowly and step halving after a fresh one.
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "cosserat/internal/dynamics_impl.hpp"

namespace tcasim::cosserat {

using namespace dynamics_names;

Eigen::VectorXd RodDynamics::Impl::unknown_scale() const {
  Eigen::VectorXd s;
  unknown_scale(s);
  return s;
}

void RodDynamics::Impl::unknown_scale(Eigen::VectorXd& s) const {
  s.resize(unknowns());
  s.head<6>() = scale.segment<6>(kN);
  for (int j = 0; j < n_tca; ++j) s[6 + j] = scale[kT + j];
  for (int k = 1; k < M; ++k) s.segment(n0() + (k - 1) * D, D) = scale;
}

DynamicsSummary RodDynamics::Impl::solve(Eigen::VectorXd& zz) {
  DynamicsSummary sum;
  const int n = unknowns();
  // (set_scales() has set scale_z_; the vectors are the kept workspace)
  const Eigen::VectorXd& scale_z = scale_z_;
  Eigen::VectorXd &r = r_, &z_old = z_old_, &dz = dz_, &u = u_;
  r.resize(n);
  z_old = zz;
  dz.setZero(n);
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
        sum.message = dense ? "the dense LU factorization of the multiple-shooting Jacobian is "
                              "singular (a pivot below 1e-14 of the largest)"
                            : "SparseLU could not factorize the multiple-shooting Jacobian";
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
    // the residual (or nearly converge, below); then a fresh Jacobian at the last accepted
    // point.
    if (step_taken && !step_from_fresh && stale_iterations >= kStaleIterations) {
      need_fresh = true;
      stale_iterations = 0;
      continue;  // re-evaluates at zz with a fresh Jacobian
    }
    // A stale chord step that contracts, but by less than half, is kept when two more at its
    // rate reach the tolerance: near the solution a fresh Jacobian costs more than they do.
    const double rate = rn / rn_old;
    const bool nearly_converged =
        step_taken && !step_from_fresh && rate < 1.0 && rn * rate * rate <= opt.tolerance;
    if (step_taken && !(rn < (step_from_fresh ? 1.0 : 0.5) * rn_old) && !nearly_converged) {
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
    // u = J^-1 r; the step is -u (the same numbers as J^-1 (-r): every operation of the
    // solve commutes with the sign).
    if (dense) {
      dense_solve(r, u);
    } else {
      u = lu_.solve(r);
    }
    if (!u.allFinite()) {
      sum.status = DynamicsSummary::Status::kSingularJacobian;
      sum.message = "the Newton step is not finite";
      return sum;
    }
    dz = -(u.cwiseProduct(scale_z));
    lambda = 1.0;
    zz = z_old + dz;
    step_taken = true;
    step_from_fresh = fresh;
    if (!fresh) ++stale_iterations;
    ++sum.iterations;
  }
}

bool RodDynamics::newton_system(const Eigen::VectorXd& u, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
  Impl& d = *impl_;
  if (u.size() != d.unknowns()) return false;
  const bool ok = d.evaluate(u.cwiseProduct(d.unknown_scale()), r, J != nullptr);
  if (ok && J) *J = d.dense ? d.J_dense_ : Eigen::MatrixXd(d.J_);
  d.lu_valid = false;  // the factorization is no longer the one of the step's iterate
  return ok;
}

Eigen::VectorXd RodDynamics::scaled_unknowns() const {
  return impl_->z.cwiseQuotient(impl_->unknown_scale());
}

}  // namespace tcasim::cosserat
