// Rod dynamics: the time-discretized rod equations at one point (the section's constitutive
// solve with Kelvin-Voigt damping and the strings, the BDF-alpha rates) and their Jacobian.
#include <cmath>

#include "cosserat/internal/dynamics_impl.hpp"

namespace tcasim::cosserat {

using namespace dynamics_names;

bool RodDynamics::Impl::rhs(double /*s: the slot's, whose routing is slot_r()*/,
                            const Eigen::VectorXd& y, int slot, Eigen::VectorXd& dy,
                            dynamics::StageJacobian* A) {
  const Eigen::Map<const Mat3> R(y.data() + kR);
  const Vec3 Nb = y.segment<3>(kN), Mb = y.segment<3>(kM);
  const Vec3 q = y.segment<3>(kQ), w = y.segment<3>(kW);
  const PointRates& H = hist[slot];
  const dynamics::SectionAt& sp = section_of(slot);
  const Vec3 f_W = sp.rho_A * g_W;
  PointData& X = trial[slot];
  const double c = c0_active;
  // Effective stiffness of the step: K + c0 B (Kelvin-Voigt, docs/conventions.md).
  const Vec3 Kt_se = sp.K_se + c * sp.B_se, Kt_bt = sp.K_bt + c * sp.B_bt;
  const Vec3 Kt_se_inv = Kt_se.cwiseInverse(), Kt_bt_inv = Kt_bt.cwiseInverse();
  // Section constitutive law solved for the strains xi = (e, omega):
  //   K_se e + B_se (c0 e + e_h) + sum c_i T_i qh_i = N,
  //   K_bt (omega - omega*) + B_bt (c0 omega + omega_h) + sum c_i T_i r_i x qh_i = M.
  const Vec3 bN = Nb - sp.B_se.cwiseProduct(H.e);
  const Vec3 bM = Mb + sp.K_bt.cwiseProduct(sp.omega_star) - sp.B_bt.cwiseProduct(H.omega);
  // count times tension per actuator: prescribed, or the TCA tension state T_j of y.
  std::vector<double>& cTl = cT_eval;
  cTl = cT;
  for (int j = 0; j < n_tca; ++j) cTl[tca_actuator[j]] = count[tca_actuator[j]] * y[kT + j];
  // A string outside its span carries nothing here; the routing on the slot's side of a knot.
  if (string_knots) {
    for (int i = 0; i < n_act; ++i)
      if (!runs(slot, i)) cTl[i] = 0.0;
  }
  bool strings = false;
  for (int i = 0; i < n_act; ++i) strings = strings || cTl[i] != 0.0;
  Vec3 e, om;
  Mat6 Z;  // d xi / d (N, M)
  if (!strings) {
    e = Kt_se_inv.cwiseProduct(bN);
    om = Kt_bt_inv.cwiseProduct(bM);
    if (A) {
      Z.setZero();
      Z.diagonal() << Kt_se_inv, Kt_bt_inv;
    }
  } else {
    e = X.e;
    om = X.omega;
    bool done = false;
    const double force_scale = Nb.norm() + Mb.norm() / L + 1e-300;
    for (int it = 0; it < 30 && !done; ++it) {
      internal::StringSystem sys(Kt_se, Kt_bt, Kt_se_inv, Kt_bt_inv);
      Vec3 gN = Kt_se.cwiseProduct(e) - bN;
      Vec3 gM = Kt_bt.cwiseProduct(om) - bM;
      double load = force_scale;
      for (int i = 0; i < n_act; ++i) {
        if (cTl[i] == 0.0) continue;
        const Vec3 &r = slot_r(slot, i), &dr = slot_dr(slot, i);
        const Vec3 qi = e + Vec3::UnitZ() + om.cross(r) + dr;
        const double qn = qi.norm();
        const Vec3 qh = qi / qn;
        gN += cTl[i] * qh;
        gM += cTl[i] * r.cross(qh);
        sys.add(r, cTl[i] / qn, qh);
        load += std::abs(cTl[i]);
      }
      sys.factor();
      Vec6 dx;
      dx << gN, gM;
      const double gnorm = std::max(gN.lpNorm<Eigen::Infinity>(), gM.lpNorm<Eigen::Infinity>() / L);
      sys.solve_in_place(dx);
      e -= dx.head<3>();
      om -= dx.tail<3>();
      if (!dx.allFinite()) return false;
      const double step =
          dx.head<3>().lpNorm<Eigen::Infinity>() + L * dx.tail<3>().lpNorm<Eigen::Infinity>();
      const double size = e.lpNorm<Eigen::Infinity>() + L * om.lpNorm<Eigen::Infinity>() + 1e-300;
      // Newton converges quadratically here: after a correction of relative size d the next
      // one is of order d^2, so without a Jacobian to form, a correction below
      // kQuadraticStop (d^2 at round-off) ends the iteration one solve early; the Jacobian
      // path keeps iterating to round-off so that Z is the factorization at the solution.
      done = gnorm <= 1e-15 * load || step <= 1e-15 * size ||
             (A == nullptr && step <= kQuadraticStop * size);
      if (done && A) {
        Z.setIdentity();
        sys.solve_in_place(Z);
      }
    }
    if (!done) return false;
  }
  const Vec3 nu = e + Vec3::UnitZ();
  X.e = e;
  X.omega = om;
  X.q = q;
  X.w = w;
  X.p = y.segment<3>(kP);
  const Vec3 q_t = c * q + H.q, w_t = c * w + H.w;
  const Vec3 e_t = c * e + H.e, om_t = c * om + H.omega;
  const Vec3 Jw = sp.rho_J.cwiseProduct(w);
  // [Till2019] (body frame): p' = R nu, R' = R hat(omega),
  //   N' = -omega x N + rho A (w x q + q_t) - R^T f_ext,
  //   M' = -omega x M - nu x N + w x rho J w + rho J w_t,
  //   q' = nu_t - omega x q + w x nu,  w' = omega_t - omega x w.
  dy.segment<3>(kP) = R * nu;
  Eigen::Map<Mat3>(dy.data() + kR) = R * hat(om);
  dy.segment<3>(kN) = -om.cross(Nb) + sp.rho_A * (w.cross(q) + q_t) - R.transpose() * f_W;
  dy.segment<3>(kM) = -om.cross(Mb) - nu.cross(Nb) + w.cross(Jw) + sp.rho_J.cwiseProduct(w_t);
  dy.segment<3>(kQ) = e_t - om.cross(q) + w.cross(nu);
  dy.segment<3>(kW) = om_t - om.cross(w);
  for (int i = 0; i < n_act; ++i) {
    if (!runs(slot, i)) {
      dy[kDelta + i] = 0.0;
      continue;
    }
    const Vec3 qi = nu + om.cross(slot_r(slot, i)) + slot_dr(slot, i);
    dy[kDelta + i] = qi.norm() - length_ratio[i];
  }
  if (n_tca > 0) dy.segment(kT, n_tca).setZero();  // T_j' = 0: one tension along the string
  if (!A) return true;
  // Jacobian: direct part (xi fixed) plus df/dxi Z on the (N, M) rows of the state and on
  // the TCA tensions (StageJacobian).
  StageJacobian& Aj = *A;
  const Mat3 I = Mat3::Identity();
  Aj.kT = kT;
  Aj.nu = nu;
  Aj.f_W = f_W;
  Aj.Om = hat(om);
  Aj.hat_nu = hat(nu);
  Aj.B_NQ = sp.rho_A * (hat(w) + c * I);
  Aj.B_NW = -sp.rho_A * hat(q);
  Aj.B_MW = hat(w) * sp.rho_J.asDiagonal() - hat(Jw) + c * Mat3(sp.rho_J.asDiagonal());
  Aj.Z = Z;
  // df/dxi (D x 6).
  Eigen::Matrix<double, Eigen::Dynamic, 6>& Fx = Aj.Fx;
  Fx.setZero(D, 6);
  Fx.block<3, 3>(kP, 0) = R;
  for (int j = 0; j < 3; ++j) Fx.block<3, 3>(kR + 3 * j, 3) = -R * hat(Vec3::Unit(j));
  Fx.block<3, 3>(kN, 3) = hat(Nb);
  Fx.block<3, 3>(kM, 0) = hat(Nb);
  Fx.block<3, 3>(kM, 3) = hat(Mb);
  Fx.block<3, 3>(kQ, 0) = c * I + hat(w);
  Fx.block<3, 3>(kQ, 3) = hat(q);
  Fx.block<3, 3>(kW, 3) = c * I + hat(w);
  for (int i = 0; i < n_act; ++i) {
    if (!runs(slot, i)) continue;
    const Vec3& r = slot_r(slot, i);
    const Vec3 qi = nu + om.cross(r) + slot_dr(slot, i);
    const Vec3 qh = qi.normalized();
    Fx.block<1, 3>(kDelta + i, 0) = qh.transpose();
    Fx.block<1, 3>(kDelta + i, 3) = r.cross(qh).transpose();
  }
  // TCA tensions: f depends on T_j only through the strains, d xi / d T_j = Z v_j with
  // v_j = -c_i (qh_i, r_i x qh_i) from the constitutive law.
  Aj.v.resize(n_tca);
  for (int j = 0; j < n_tca; ++j) {
    const int i = tca_actuator[j];
    Aj.v[j].setZero();
    if (!runs(slot, i)) continue;
    const Vec3& r = slot_r(slot, i);
    const Vec3 qh = (nu + om.cross(r) + slot_dr(slot, i)).normalized();
    Vec6 g;
    g << qh, r.cross(qh);
    Aj.v[j] = -count[i] * g;
  }
  return true;
}

void StageJacobian::apply(const Eigen::MatrixXd& dY, Eigen::MatrixXd& dK) const {
  // Column by column, in fixed-size blocks (the layout of dynamics.hpp; R's column j at kR + 3 j).
  const int D = static_cast<int>(dY.rows());
  dK.resize(D, dY.cols());
  for (Eigen::Index col = 0; col < dY.cols(); ++col) {
    const double* y = dY.col(col).data();
    double* k = dK.col(col).data();
    // The strains' part: Fx Z (dY_NM + sum_j v_j dY_Tj).
    Vec6 x = Eigen::Map<const Vec6>(y + kN);
    for (std::size_t j = 0; j < v.size(); ++j) x += v[j] * y[kT + static_cast<int>(j)];
    const Vec6 zx = Z * x;
    Eigen::Map<Eigen::VectorXd>(k, D).noalias() = Fx * zx;
    // The direct part (xi fixed).
    const Eigen::Map<const Mat3> dR(y + kR);
    const Eigen::Map<const Vec3> dN(y + kN), dM(y + kM), dQ(y + kQ), dW(y + kW);
    Eigen::Map<Vec3>(k + kP) += dR * nu;  // d(R nu)
    Eigen::Map<Mat3>(k + kR) += dR * Om;  // d(R hat(omega))
    Eigen::Map<Vec3>(k + kN) += B_NQ * dQ + B_NW * dW - Om * dN - dR.transpose() * f_W;
    Eigen::Map<Vec3>(k + kM) += B_MW * dW - Om * dM - hat_nu * dN;
    Eigen::Map<Vec3>(k + kQ) -= Om * dQ + hat_nu * dW;
    Eigen::Map<Vec3>(k + kW) -= Om * dW;
  }
}

bool RodDynamics::Impl::rhs_residual(double s, const double* y, int slot, double* dy) {
  // Strings under tension: the section's constitutive solve of rhs().
  bool strings = false;
  for (int i = 0; i < n_act; ++i) strings = strings || cT[i] != 0.0;
  for (int j = 0; j < n_tca; ++j) strings = strings || y[kT + j] != 0.0;
  if (strings) {
    ws_y_ = Eigen::Map<const Eigen::VectorXd>(y, D);
    if (!rhs(s, ws_y_, slot, ws_dy_, nullptr)) return false;
    Eigen::Map<Eigen::VectorXd>(dy, D) = ws_dy_;
    return true;
  }
  // The equations of rhs() without strings: the strains follow the section law directly,
  //   e = (N - B_se e_h) / (K_se + c0 B_se),
  //   omega = (M + K_bt omega* - B_bt omega_h) / (K_bt + c0 B_bt).
  const Eigen::Map<const Mat3> R(y + kR);
  const Eigen::Map<const Vec3> Nb(y + kN), Mb(y + kM), q(y + kQ), w(y + kW);
  const PointRates& H = hist[slot];
  const dynamics::SectionAt& sp = section_of(slot);
  const dynamics::SectionConstants& kc = constants_of(slot);
  const double c = c0_active;
  // (in rhs()'s order of operations: the same numbers)
  const Vec3 e = kc.Kt_se_inv.cwiseProduct(Nb - sp.B_se.cwiseProduct(H.e));
  const Vec3 om =
      kc.Kt_bt_inv.cwiseProduct(Mb + kc.K_bt_omega_star - sp.B_bt.cwiseProduct(H.omega));
  PointData& X = trial[slot];
  X.e = e;
  X.omega = om;
  X.q = q;
  X.w = w;
  X.p = Eigen::Map<const Vec3>(y + kP);
  const Vec3 nu = e + Vec3::UnitZ();
  const Vec3 q_t = c * q + H.q, w_t = c * w + H.w;
  const Vec3 e_t = c * e + H.e, om_t = c * om + H.omega;
  const Vec3 Jw = sp.rho_J.cwiseProduct(w);
  Eigen::Map<Vec3>(dy + kP) = R * nu;
  // R hat(omega), column by column: column j is R (omega x e_j).
  Eigen::Map<Mat3> dR(dy + kR);
  dR.col(0) = om.z() * R.col(1) - om.y() * R.col(2);
  dR.col(1) = om.x() * R.col(2) - om.z() * R.col(0);
  dR.col(2) = om.y() * R.col(0) - om.x() * R.col(1);
  Eigen::Map<Vec3>(dy + kN) =
      -om.cross(Nb) + sp.rho_A * (w.cross(q) + q_t) - R.transpose() * kc.f_W;
  Eigen::Map<Vec3>(dy + kM) =
      -om.cross(Mb) - nu.cross(Nb) + w.cross(Jw) + sp.rho_J.cwiseProduct(w_t);
  Eigen::Map<Vec3>(dy + kQ) = e_t - om.cross(q) + w.cross(nu);
  Eigen::Map<Vec3>(dy + kW) = om_t - om.cross(w);
  for (int i = 0; i < n_act; ++i) {
    if (!runs(slot, i)) {  // outside its span (as in rhs())
      dy[kDelta + i] = 0.0;
      continue;
    }
    const Vec3 qi = nu + om.cross(slot_r_[slot * n_act + i]) + slot_dr_[slot * n_act + i];
    dy[kDelta + i] = qi.norm() - length_ratio[i];
  }
  for (int j = 0; j < n_tca; ++j) dy[kT + j] = 0.0;
  return true;
}

}  // namespace tcasim::cosserat
