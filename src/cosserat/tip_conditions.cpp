#include "cosserat/internal/tip_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/error.hpp"
#include "rod/loads.hpp"

namespace tcasim::cosserat::internal {

using namespace state_layout;

TipConditions::TipConditions(const rod::RodModel& m, std::unique_ptr<Layout> l, bool sensitivities)
    : RodRhs(m, std::move(l), sensitivities) {
  // The states and unknowns carry nu - nu* (shooting.hpp), so internal forces keep their
  // digits at any stiffness ratio EA L^2 / EI: no stiffness floor. The tip balance sums
  // the applied forces, so its round-off is eps times the largest of them: F_c is the
  // larger of the bending force scale and the model's own loads.
  Fc = rod::characteristic_force_N(model, rod::Loads::from_model(model));
  dphi_dT.assign(n_act, 0.0);
  dphi_ddelta.assign(n_act, 0.0);
}

// docs/conventions.md "Tip conditions" (body frame), scaled.
bool TipConditions::tip_residual(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& yL, Eigen::VectorXd& r) {
  r.resize(nx);
  layout->tip_rows(*this, act, lambda, x, yL, r);
  return tca_rows(x, yL, r);
}

bool TipConditions::tca_rows(const Eigen::VectorXd& x, const Eigen::VectorXd& yL,
                             Eigen::VectorXd& r) {
  for (int i = 0; i < n_act; ++i) {
    const int k = unknown_of[i];
    if (k < 0) continue;
    try {
      const tca::ContactResidual c = tca::contact_residual(
          *model.actuators[i].drive.tca, x[k], yL[delta_offset + i], scaled_segments[i]);
      r[k] = c.phi_N / Fc;
      dphi_dT[i] = c.dphi_dF;
      dphi_ddelta[i] = c.dphi_ddelta_N_m;
    } catch (const DomainError&) {
      return false;
    }
  }
  return all_finite(r);
}

bool TipConditions::tip_jacobian(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& y, const Eigen::VectorXd& Y,
                                 Eigen::MatrixXd& J) const {
  J.resize(nx, nx);
  layout->tip_rows_jacobian(*this, act, lambda, x, y, Y, J);
  // TCA rows: dphi = dphi/dT dT + dphi/d delta d delta(L).
  for (int j = 0; j < nx; ++j) {
    const double* yj = Y.data() + dim * (j + 1);
    for (int i = 0; i < n_act; ++i) {
      const int k = unknown_of[i];
      if (k < 0) continue;
      J(k, j) = ((k == j ? dphi_dT[i] : 0.0) + dphi_ddelta[i] * yj[delta_offset + i]) / Fc;
    }
  }
  return J.allFinite();
}

Vec3 TipConditions::reaction_W(const Eigen::VectorXd& x) const {
  if (n_con == 3) return x.segment<3>(k_con);
  if (n_con == 1) return x[k_con] * con_normal_W;
  return Vec3::Zero();
}

void TipConditions::equilibrium(const rod::Loads& act, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& yL, Summary& summary) const {
  const Mat3& R0 = model.R_WB0;
  const Vec3 p0 = model.base_position_W_m;
  const Vec3 n0 = R0 * K_nu.cwiseProduct(x.head<3>());  // x holds nu(0) - nu*
  const Vec3 m0 = R0 * K_omega.cwiseProduct(x.segment<3>(3) - omega_star);
  const Vec3 w = f_ext_W;
  const Vec3 pL = yL.segment<3>(kP);
  const Vec3 c = yL.segment<3>(kC);
  const Vec3 F_tip =
      rod::tip_force_with_weight_W_N(model, act) + reaction_W(x);  // applied load plus the holder's
  // weight_length = L for a uniform body (int_0^L psi A / psi A_ref ds otherwise, with c the
  // matching weighted integral of p).
  Vec3 n_exp = F_tip + weight_length * w;
  Vec3 m_exp = act.tip_moment_W_Nm + (pL - p0).cross(F_tip) + (c - weight_length * p0).cross(w);
  for (int i = 0; i < n_act; ++i) {
    // A string anchored at both ends inside the body loads it with a self-balanced system.
    if (!from_base(i)) continue;
    const rod::Routing& ro = model.actuators[i].routing;
    const Vec3 r0 = ro.r(0.0);
    const Vec3 t0 =
        R0 * (nu_star + x.head<3>() + x.segment<3>(3).cross(r0) + ro.dr(0.0)).normalized();
    n_exp -= cT[i] * t0;
    m_exp -= (R0 * r0).cross(cT[i] * t0);
  }
  summary.force_imbalance_W_N = n0 - n_exp;
  summary.moment_imbalance_W_Nm = m0 - m_exp;
  if (!summary.force_imbalance_W_N.allFinite()) summary.force_imbalance_W_N.setZero();
  if (!summary.moment_imbalance_W_Nm.allFinite()) summary.moment_imbalance_W_Nm.setZero();
}

}  // namespace tcasim::cosserat::internal
