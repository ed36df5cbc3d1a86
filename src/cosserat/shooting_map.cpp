// The shooting map: r(x) and dr/dx by one IVP from the unknowns x on the active level, and
// the memo of the last accepted IVP.
#include "cosserat/internal/shooting_impl.hpp"

namespace tcasim::cosserat {

using namespace stage_names;

bool ShootingSolver::Impl::residual(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                                    Eigen::VectorXd& r) {
  if (!all_finite(x)) return false;
  set_parameters(act, lambda, x);
  samples.valid = false;
  if (memo_answers(x)) {
    y = y_acc;  // same IVP as the last accepted one: no integration
    return tip_residual(act, lambda, x, y, r);
  }
  initial_state(x, y);
  ++ivp_count;
  const bool record = record_samples && level == &fine_level;
  if (record) {
    samples.s.clear();
    samples.y.clear();
  }
  static const ode::Observer kNoObserver;
  if (!level->integrate(rhs, L, y, record ? sample_recorder : kNoObserver)) return false;
  samples.valid = record;
  return tip_residual(act, lambda, x, y, r);
}

bool ShootingSolver::Impl::residual_and_jacobian(const rod::Loads& act, double lambda,
                                                 const Eigen::VectorXd& x, Eigen::VectorXd& r,
                                                 Eigen::MatrixXd& J) {
  if (!all_finite(x)) return false;
  set_parameters(act, lambda, x);
  samples.valid = false;
  Y.setZero();
  initial_state(x, y);
  Y.head(dim) = y;
  // d y(0) / d x_j = e_{strain_offset + j} for the strain unknowns (the layout's)
  for (int j = 0; j < x_tca; ++j) Y[dim * (j + 1) + strain_offset + j] = 1.0;
  ++ivp_count;
  if (!level->integrate_sensitivities(rhs_sens, L, Y)) return false;
  y = Y.head(dim);
  if (!tip_residual(act, lambda, x, y, r)) return false;
  return tip_jacobian(act, lambda, x, y, Y, J);
}

bool ShootingSolver::Impl::memo_answers(const Eigen::VectorXd& x,
                                        const IntegrationLevel* on) const {
  return memo_valid && acc_level == (on != nullptr ? on : level) && x_acc.size() == x.size() &&
         x_acc == x && acc_cT == cT && acc_f_ext == f_ext_W &&
         acc_omega_star_fraction == omega_star_fraction;
}

void ShootingSolver::Impl::remember(double lambda, const Eigen::VectorXd& x) {
  // The accepted point's samples: those of the last IVP (whose y(L) is y) if it recorded
  // them; kept if the memo already holds this IVP (y came from it); else none.
  if (samples.valid) {
    std::swap(acc_samples, samples);
    samples.valid = false;
  } else if (!memo_answers(x)) {
    acc_samples.valid = false;
  }
  acc_full_load = lambda == 1.0 && level == &fine_level && omega_star_fraction == 1.0;
  acc_omega_star_fraction = omega_star_fraction;
  memo_valid = y.allFinite();
  acc_cT = cT;
  acc_f_ext = f_ext_W;
  acc_dphi_dT = dphi_dT;
  acc_dphi_ddelta = dphi_ddelta;
  acc_level = level;
  y_acc = y;
  x_acc = x;
}

}  // namespace tcasim::cosserat
