#include "cosserat/tip_conditions.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "cosserat/planar.hpp"
#include "rod/loads.hpp"

namespace tcasim::cosserat::internal {

using namespace state_layout;

TipConditions::TipConditions(const rod::RodModel& m, bool planar_layout, bool sensitivities)
    : RodRhs(m, planar_layout, sensitivities) {
  // The states and unknowns carry nu - nu* (shooting.hpp), so internal forces keep their
  // digits at any stiffness ratio EA L^2 / EI: no stiffness floor. The tip balance sums
  // the applied forces, so its round-off is eps times the largest of them: F_c is the
  // larger of the bending force scale and the model's own loads.
  Fc = rod::characteristic_force_N(model, rod::Loads::from_model(model));
  dphi_dT.assign(n_act, 0.0);
  dphi_ddelta.assign(n_act, 0.0);
}

// docs/conventions.md "Tip conditions" (body frame), scaled.
bool TipConditions::tip_residual(const Actuation& act, double lambda, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& yL, Eigen::VectorXd& r) {
  r.resize(nx);
  if (planar) {
    // The in-plane rows (force x, z; moment y) of the 3-D residual; the others are zero.
    const Vec3 F_B0 =
        model.R_WB0.transpose() * (lambda * rod::tip_force_with_weight_W_N(model, act));
    const double M_y = model.R_WB0.col(1).dot(lambda * act.tip_moment_W_Nm);
    double w[3];
    planar::tip_wrench(prod, omega_star.y(), F_B0.x(), F_B0.z(), M_y, yL.data(), w);
    r[0] = w[0] / Fc;
    r[1] = w[1] / Fc;
    r[2] = w[2] / (Fc * L);
    return tca_rows(x, yL, planar::kDelta, r);
  }
  const Eigen::Map<const Mat3> R(yL.data() + kR);
  const Vec3 e = yL.segment<3>(kNu);  // nu - nu*
  const Vec3 nu = nu_star + e;
  const Vec3 omega = yL.segment<3>(kOmega);
  // The holder's reaction (an unknown, not scaled by lambda) adds to the applied tip force.
  Vec3 rn = K_nu_tip.cwiseProduct(e) -
            R.transpose() * (lambda * rod::tip_force_with_weight_W_N(model, act) + reaction_W(x));
  Vec3 rm = K_omega_tip.cwiseProduct(omega - omega_star_tip) -
            R.transpose() * (lambda * act.tip_moment_W_Nm);
  for (int i = 0; i < n_act; ++i) {
    if (cT[i] == 0.0 || !to_tip(i)) continue;  // a string anchored before L: not at the tip
    const Vec3 ri = model.actuators[i].routing.r(L);
    const Vec3 q = nu + omega.cross(ri) + model.actuators[i].routing.dr(L);
    const Vec3 qh = q.normalized();
    rn += cT[i] * qh;
    rm += cT[i] * ri.cross(qh);
  }
  r.head<3>() = rn / Fc;
  r.segment<3>(3) = rm / (Fc * L);
  // Tip constraint: position error (pinned) or its normal component, scaled by L.
  if (n_con == 3) r.segment<3>(k_con) = (yL.segment<3>(kP) - con_target_W) / L;
  if (n_con == 1) r[k_con] = con_normal_W.dot(yL.segment<3>(kP) - con_target_W) / L;
  return tca_rows(x, yL, kDelta, r);
}

bool TipConditions::tca_rows(const Eigen::VectorXd& x, const Eigen::VectorXd& yL, int delta0,
                             Eigen::VectorXd& r) {
  for (int i = 0; i < n_act; ++i) {
    const int k = unknown_of[i];
    if (k < 0) continue;
    try {
      const tca::ContactResidual c = tca::contact_residual(*model.actuators[i].drive.tca, x[k],
                                                           yL[delta0 + i], scaled_segments[i]);
      r[k] = c.phi_N / Fc;
      dphi_dT[i] = c.dphi_dF;
      dphi_ddelta[i] = c.dphi_ddelta_N_m;
    } catch (const DomainError&) {
      return false;
    }
  }
  return all_finite(r);
}

bool TipConditions::tip_jacobian(const Actuation& act, double lambda, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& y, const Eigen::VectorXd& Y,
                                 Eigen::MatrixXd& J) const {
  J.resize(nx, nx);
  if (planar) return planar_jacobian(act, lambda, Y, J);
  // Chain rule through the tip conditions: dr = (dr/dy) Y(L) + dr/dT.
  const Eigen::Map<const Mat3> R(y.data() + kR);
  const Vec3 nu = nu_star + y.segment<3>(kNu), omega = y.segment<3>(kOmega);
  const Vec3 F_e = lambda * rod::tip_force_with_weight_W_N(model, act) + reaction_W(x),
             M_e = lambda * act.tip_moment_W_Nm;
  for (int j = 0; j < nx; ++j) {
    const double* yj = Y.data() + dim * (j + 1);
    const Eigen::Map<const Mat3> dR(yj + kR);
    const Vec3 dnu(yj + kNu), dom(yj + kOmega);
    Vec3 drn = K_nu_tip.cwiseProduct(dnu) - dR.transpose() * F_e;
    Vec3 drm = K_omega_tip.cwiseProduct(dom) - dR.transpose() * M_e;
    for (int i = 0; i < n_act; ++i) {
      const double dcT = unknown_of[i] == j ? count[i] : 0.0;
      if ((cT[i] == 0.0 && dcT == 0.0) || !to_tip(i)) continue;
      const rod::Routing& ro = model.actuators[i].routing;
      const Vec3 ri = ro.r(L);
      const Vec3 q = nu + omega.cross(ri) + ro.dr(L);
      const double qn = q.norm();
      const Vec3 qh = q / qn;
      const Vec3 dq = dnu + dom.cross(ri);
      const Vec3 dqh = (dq - qh * qh.dot(dq)) / qn;
      const Vec3 dF = dcT * qh + cT[i] * dqh;
      drn += dF;
      drm += ri.cross(dF);
    }
    // A reaction unknown enters only the tip force (its IVP sensitivity is zero).
    if (j >= k_con) drn -= R.transpose() * (n_con == 3 ? Vec3::Unit(j - k_con) : con_normal_W);
    J.block<3, 1>(0, j) = drn / Fc;
    J.block<3, 1>(3, j) = drm / (Fc * L);
    for (int i = 0; i < n_act; ++i) {
      const int k = unknown_of[i];
      if (k < 0) continue;
      J(k, j) = ((k == j ? dphi_dT[i] : 0.0) + dphi_ddelta[i] * yj[kDelta + i]) / Fc;
    }
    if (n_con == 3) J.block<3, 1>(k_con, j) = Vec3(yj + kP) / L;
    if (n_con == 1) J(k_con, j) = con_normal_W.dot(Vec3(yj + kP)) / L;
  }
  return J.allFinite();
}

bool TipConditions::planar_jacobian(const Actuation& act, double lambda, const Eigen::VectorXd& Y,
                                    Eigen::MatrixXd& J) const {
  const Vec3 F_B0 = model.R_WB0.transpose() * (lambda * rod::tip_force_with_weight_W_N(model, act));
  double dw[3 * planar::kMaxDirections];
  planar::tip_wrench_sens(prod, F_B0.x(), F_B0.z(), dim, nx, Y.data(), dw);
  for (int j = 0; j < nx; ++j) {
    J(0, j) = dw[3 * j] / Fc;
    J(1, j) = dw[3 * j + 1] / Fc;
    J(2, j) = dw[3 * j + 2] / (Fc * L);
    const double* yj = Y.data() + dim * (j + 1);
    for (int i = 0; i < n_act; ++i) {
      const int k = unknown_of[i];
      if (k >= 0)
        J(k, j) = ((k == j ? dphi_dT[i] : 0.0) + dphi_ddelta[i] * yj[planar::kDelta + i]) / Fc;
    }
  }
  return J.allFinite();
}

Vec3 TipConditions::reaction_W(const Eigen::VectorXd& x) const {
  if (n_con == 3) return x.segment<3>(k_con);
  if (n_con == 1) return x[k_con] * con_normal_W;
  return Vec3::Zero();
}

void TipConditions::equilibrium(const Actuation& act, const Eigen::VectorXd& x,
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
