#include "cosserat/internal/rhs.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#include "cosserat/internal/string_system.hpp"
#include "rod/closed_form.hpp"

namespace tcasim::cosserat::internal {

using namespace state_layout;

RodRhs::RodRhs(const rod::RodModel& m, std::unique_ptr<Layout> l, bool sensitivities)
    : RodProblem(m, l->dims()), layout(std::move(l)) {
  cT.assign(n_act, 0.0);
  scaled_segments.resize(n_act);
  cache.resize(n_act);
  uniform_local = {K_nu, K_omega, K_nu_inv, K_omega_inv, omega_star, 1.0};
  if (!knots.empty()) {
    pieces.knots = knots;
    pieces.enter = [this](double lo, double hi) {
      piece_mid = 0.5 * (lo + hi);
      piece = static_cast<std::size_t>(std::lower_bound(knots.begin(), knots.end(), lo) -
                                       knots.begin());
    };
    pieces.jump = [this](std::size_t k, Eigen::VectorXd& yy) { return strain_jump(k, yy, 0); };
    pieces.jump_sens = [this](std::size_t k, Eigen::VectorXd& yy) {
      return strain_jump(k, yy, nx);
    };
  }
  const bool with_sensitivities = sensitivities && nx <= kMaxSensitivityUnknowns;
  if (with_sensitivities) rhs_ws.resize(6, nx);
  layout->bind(*this, with_sensitivities);
}

RodRhs::Local RodRhs::model_local(double s, rod::Side side) const {
  Local k;
  model_properties(s, side, k.Kn, k.Kw, k.ws, k.wf);
  model.property_slopes(s, side, k.dKn, k.dKw, k.dws);
  k.Kn_inv = k.Kn.cwiseInverse();
  k.Kw_inv = k.Kw.cwiseInverse();
  return k;
}

std::size_t RodRhs::LocalMemo::slot_of(double s, rod::Side side) const {
  std::uint64_t bits;
  std::memcpy(&bits, &s, sizeof bits);
  // Fibonacci hashing (the top bits of the product with 2^64 / golden ratio: neighbouring
  // grid points differ in few mantissa bits); the side flips the lowest bit.
  bits = (bits ^ (side == rod::Side::kLeft ? 1u : 0u)) * 0x9E3779B97F4A7C15ull;
  return static_cast<std::size_t>(bits >> (64 - slot_bits_));
}

const RodRhs::Local* RodRhs::LocalMemo::find(double s, rod::Side side) const {
  if (entries_.empty()) return nullptr;
  const std::size_t mask = slot_.size() - 1;
  for (std::size_t i = slot_of(s, side);; i = (i + 1) & mask) {
    const int e = slot_[i];
    if (e < 0) return nullptr;
    const Entry& entry = entries_[static_cast<std::size_t>(e)];
    if (entry.s == s && entry.side == side) return &entry.k;
  }
}

const RodRhs::Local& RodRhs::LocalMemo::insert(double s, rod::Side side, const Local& k) {
  if (entries_.size() >= kMaxEntries) {
    overflow_ = k;
    return overflow_;
  }
  entries_.push_back({s, side, k});
  const auto place = [this](std::size_t e) {
    const std::size_t mask = slot_.size() - 1;
    std::size_t i = slot_of(entries_[e].s, entries_[e].side);
    while (slot_[i] >= 0) i = (i + 1) & mask;
    slot_[i] = static_cast<int>(e);
  };
  if (2 * entries_.size() > slot_.size()) {  // load above 1/2: double (from 256) and rehash
    slot_bits_ = std::max(8, slot_bits_ + 1);
    slot_.assign(std::size_t{1} << slot_bits_, -1);
    for (std::size_t e = 0; e < entries_.size(); ++e) place(e);
  } else {
    place(entries_.size() - 1);
  }
  return entries_.back().k;
}

// docs/conventions.md "Body-frame ODEs solved by the shooting solver".
void RodRhs::eval_rhs(double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) const {
  const Eigen::Map<const Mat3> R(yy.data() + kR);
  const Vec3 e = yy.segment<3>(kNu);  // nu - nu* (shooting.hpp layout)
  const Vec3 nu = nu_star + e;
  const Vec3 omega = yy.segment<3>(kOmega);
  const Local& k = local(s);
  // [Pawlowski2019] Eqs. (9)-(10): n_B = K_nu (nu - nu*), m_B = K_omega (omega - omega*).
  const Vec3 n_B = k.Kn.cwiseProduct(e);
  const Vec3 m_B = k.Kw.cwiseProduct(omega - k.ws);

  // M = K + sum_i U_i A_i U_i^T (StringSystem), A_i = c_i T_i P_i / |q_i|.
  StringSystem M(k.Kn, k.Kw, k.Kn_inv, k.Kw_inv);
  // b_nu = -omega x n_B - R^T f_ext - sum g_i;  b_omega = -omega x m_B - nu x n_B - sum r_i x g_i
  Vec3 b_nu = -omega.cross(n_B) - R.transpose() * (uniform ? f_ext_W : Vec3(k.wf * f_ext_W));
  Vec3 b_omega = -omega.cross(m_B) - nu.cross(n_B);
  if (!uniform) {
    // n_B' = K_nu e' + K_nu' e, m_B' = K_omega omega' + K_omega' (omega - omega*) - K_omega
    // omega*'.
    b_nu -= k.dKn.cwiseProduct(e);
    b_omega += k.Kw.cwiseProduct(k.dws) - k.dKw.cwiseProduct(omega - k.ws);
  }
  for (int i = 0; i < n_act; ++i) {
    if (!runs(piece, i)) {  // outside the string's span: no string, no elongation
      dy[kDelta + i] = 0.0;
      continue;
    }
    const rod::Routing& routing = model.actuators[i].routing;
    Vec3 r, dr, ddr;
    if (straight[i]) {
      r << routing.offset_m.x(), routing.offset_m.y(), 0.0;
      dr.setZero();
      ddr.setZero();
    } else {
      // Inside the current piece: at its ends, the piece's own side of a spline knot.
      const rod::Side side = s < piece_mid ? rod::Side::kRight : rod::Side::kLeft;
      r = routing.r(s, side);
      dr = routing.dr(s, side);
      ddr = routing.ddr(s, side);
    }
    // [Pawlowski2019] Eq. (19): q = nu + omega x r + r'.
    const Vec3 q = nu + omega.cross(r) + dr;
    const double q_norm = q.norm();
    dy[kDelta + i] = q_norm - length_ratio[i];  // delta_i' = |q_i| - L_i
    if (cT[i] == 0.0) continue;
    const Vec3 qh = q / q_norm;
    M.add(r, cT[i] / q_norm, qh);
    // g_i = c_i T_i [omega x qh + P (omega x r' + r'') / |q|],  P v = v - qh (qh . v)
    Vec3 g = omega.cross(qh);
    if (!straight[i]) {
      const Vec3 v = omega.cross(dr) + ddr;
      g += (v - qh * qh.dot(v)) / q_norm;
    }
    g *= cT[i];
    b_nu -= g;
    b_omega -= r.cross(g);
  }
  Vec6 z;
  z << b_nu, b_omega;
  M.factor();
  M.solve_in_place(z);
  // [Pawlowski2019] Eqs. (7)-(8): p' = R nu, R' = R hat(omega).
  dy.segment<3>(kP) = R * nu;
  Eigen::Map<Mat3>(dy.data() + kR) = R * hat(omega);
  dy.segment<6>(kNu) = z;
  // c' = p (the weight factor times p for a body whose psi A varies)
  if (uniform) {
    dy.segment<3>(kC) = yy.segment<3>(kP);
  } else {
    dy.segment<3>(kC) = k.wf * yy.segment<3>(kP);
  }
}

void RodRhs::eval_rhs_sens(double s, const Eigen::VectorXd& Ya, Eigen::VectorXd& dY) const {
  const double* yy = Ya.data();
  const Eigen::Map<const Mat3> R(yy + kR);
  const Vec3 e(yy + kNu);  // nu - nu*
  const Vec3 nu = nu_star + e;
  const Vec3 omega(yy + kOmega);
  const Local& k = local(s);
  const Vec3 f_W = uniform ? f_ext_W : Vec3(k.wf * f_ext_W);
  const Vec3 n_B = k.Kn.cwiseProduct(e);
  const Vec3 m_B = k.Kw.cwiseProduct(omega - k.ws);
  StringSystem lu(k.Kn, k.Kw, k.Kn_inv, k.Kw_inv);
  Vec3 b_nu = -omega.cross(n_B) - R.transpose() * f_W;
  Vec3 b_omega = -omega.cross(m_B) - nu.cross(n_B);
  if (!uniform) {
    b_nu -= k.dKn.cwiseProduct(e);
    b_omega += k.Kw.cwiseProduct(k.dws) - k.dKw.cwiseProduct(omega - k.ws);
  }
  for (int i = 0; i < n_act; ++i) {
    ActuatorCache& c = cache[i];
    if (!runs(piece, i)) {
      dY[kDelta + i] = 0.0;
      continue;
    }
    const rod::Routing& routing = model.actuators[i].routing;
    Vec3 ddr;
    if (straight[i]) {
      c.r << routing.offset_m.x(), routing.offset_m.y(), 0.0;
      c.dr.setZero();
      ddr.setZero();
    } else {
      const rod::Side side = s < piece_mid ? rod::Side::kRight : rod::Side::kLeft;
      c.r = routing.r(s, side);
      c.dr = routing.dr(s, side);
      ddr = routing.ddr(s, side);
    }
    const Vec3 q = nu + omega.cross(c.r) + c.dr;
    c.q_norm = q.norm();
    c.qh = q / c.q_norm;
    dY[kDelta + i] = c.q_norm - length_ratio[i];
    c.v = omega.cross(c.dr) + ddr;
    c.Pv = c.v - c.qh * c.qh.dot(c.v);
    c.gb = omega.cross(c.qh) + c.Pv / c.q_norm;  // g_i = c_i T_i gb_i
    if (cT[i] == 0.0) continue;
    lu.add(c.r, cT[i] / c.q_norm, c.qh);
    const Vec3 g = cT[i] * c.gb;
    b_nu -= g;
    b_omega -= c.r.cross(g);
  }
  Vec6 z;
  z << b_nu, b_omega;
  lu.factor();
  lu.solve_in_place(z);
  dY.segment<3>(kP) = R * nu;
  Eigen::Map<Mat3>(dY.data() + kR) = R * hat(omega);
  dY.segment<6>(kNu) = z;
  if (uniform) {
    dY.segment<3>(kC) = Ya.segment<3>(kP);
  } else {
    dY.segment<3>(kC) = k.wf * Ya.segment<3>(kP);
  }
  const Vec3 zn = z.head<3>(), zo = z.tail<3>();
  for (int i = 0; i < n_act; ++i) {
    ActuatorCache& c = cache[i];
    const Vec3 w = zn - c.r.cross(zo);  // M z = K z + sum [A_i w_i; r_i x A_i w_i]
    c.Pw = w - c.qh * c.qh.dot(w);
  }
  // Right-hand sides db_j - dM_j z of all directions, solved together.
  auto& B = rhs_ws;
  for (int j = 0; j < nx; ++j) {
    const double* yj = yy + dim * (j + 1);
    double* dyj = dY.data() + dim * (j + 1);
    const Eigen::Map<const Mat3> dR(yj + kR);
    const Vec3 dnu(yj + kNu), dom(yj + kOmega);
    const Vec3 dn_B = k.Kn.cwiseProduct(dnu), dm_B = k.Kw.cwiseProduct(dom);
    Vec3 db_nu = -dom.cross(n_B) - omega.cross(dn_B) - dR.transpose() * f_W;
    Vec3 db_om = -dom.cross(m_B) - omega.cross(dm_B) - dnu.cross(n_B) - nu.cross(dn_B);
    if (!uniform) {
      db_nu -= k.dKn.cwiseProduct(dnu);
      db_om -= k.dKw.cwiseProduct(dom);
    }
    for (int i = 0; i < n_act; ++i) {
      if (!runs(piece, i)) {
        dyj[kDelta + i] = 0.0;
        continue;
      }
      const ActuatorCache& c = cache[i];
      const Vec3 dq = dnu + dom.cross(c.r);
      const double dqn = c.qh.dot(dq);
      dyj[kDelta + i] = dqn;
      const double dcT = unknown_of[i] == j ? count[i] : 0.0;
      if (cT[i] == 0.0 && dcT == 0.0) continue;
      const Vec3 dqh = (dq - c.qh * dqn) / c.q_norm;
      // dP u = -(dqh (qh . u) + qh (dqh . u))
      const Vec3 dv = dom.cross(c.dr);
      const Vec3 dPv = -(dqh * c.qh.dot(c.v) + c.qh * dqh.dot(c.v));
      const Vec3 Pdv = dv - c.qh * c.qh.dot(dv);
      const Vec3 dgb = dom.cross(c.qh) + omega.cross(dqh) + (dPv + Pdv) / c.q_norm -
                       c.Pv * (dqn / (c.q_norm * c.q_norm));
      const Vec3 dg = dcT * c.gb + cT[i] * dgb;
      // d(A w) with w fixed: A = c T P / |q|
      const Vec3 w = zn - c.r.cross(zo);
      const Vec3 dPw = -(dqh * c.qh.dot(w) + c.qh * dqh.dot(w));
      const Vec3 dAw =
          (dcT * c.Pw + cT[i] * dPw) / c.q_norm - c.Pw * (cT[i] * dqn / (c.q_norm * c.q_norm));
      db_nu -= dg + dAw;
      db_om -= c.r.cross(dg + dAw);
    }
    B.col(j) << db_nu, db_om;
    Eigen::Map<Vec3>(dyj + kP) = dR * nu + R * dnu;
    Eigen::Map<Mat3>(dyj + kR) = dR * hat(omega) + R * hat(dom);
    Eigen::Map<Vec3>(dyj + kC) = uniform ? Vec3(yj + kP) : Vec3(k.wf * Vec3(yj + kP));
  }
  lu.solve_in_place(B);
  for (int j = 0; j < nx; ++j) Eigen::Map<Vec6>(dY.data() + dim * (j + 1) + kNu) = B.col(j);
}

namespace {

/// The total wrench W(z, s) across a section (RodRhs::strain_jump) and, if M is given, its
/// derivative dW/dz = diag(K_nu, K_omega) + sum_i U_i A_i U_i^T (the strain system matrix).
struct SectionWrench {
  Vec6 W;
  Mat6 M;
  std::vector<Vec6> u;  // per actuator: (qh_i, r_i x qh_i)
};

/// `side`: the side of the knot s the section lies on (the string tangents of a kinked
/// spline routing differ: docs/conventions.md "Spline routings").
void section_wrench(const RodRhs& p, double s, rod::Side side, std::size_t piece,
                    const RodRhs::Local& k, const Vec3& e, const Vec3& omega, SectionWrench& out) {
  out.W.head<3>() = k.Kn.cwiseProduct(e);
  out.W.tail<3>() = k.Kw.cwiseProduct(omega - k.ws);
  out.M.setZero();
  out.M.diagonal() << k.Kn, k.Kw;
  out.u.assign(p.n_act, Vec6::Zero());
  const Vec3 nu = p.nu_star + e;
  for (int i = 0; i < p.n_act; ++i) {
    if (!p.runs(piece, i)) continue;  // not crossing this side of the section: u_i = 0
    const rod::Routing& routing = p.model.actuators[i].routing;
    const Vec3 r = routing.r(s, side);
    const Vec3 q = nu + omega.cross(r) + routing.dr(s, side);
    const double q_norm = q.norm();
    const Vec3 qh = q / q_norm;
    out.u[i] << qh, r.cross(qh);
    if (p.cT[i] == 0.0) continue;
    out.W += p.cT[i] * out.u[i];
    // dq = de - r x domega = U^T dz, U = [I; hat(r)]: dW = U A U^T dz.
    Eigen::Matrix<double, 6, 3> U;
    U << Mat3::Identity(), hat(r);
    const Mat3 A = p.cT[i] * (Mat3::Identity() - qh * qh.transpose()) / q_norm;
    out.M += U * A * U.transpose();
  }
}

/// Newton on the strains (e, om) at s until the section wrench (rod and strings, side `side`,
/// piece `piece`) equals `target`, from the start in e and om: converged when the wrench
/// matches to 1e-15 of `scale`, or every row to its round-off (1e-14 of the sum of its terms'
/// magnitudes: where the rod's and the strings' parts nearly cancel, as at a free tip where
/// the strings end, the wrench is small and its round-off is that of the parts), or the step
/// is below 1e-15 of the strains (length L). False when a step is not finite or 30 steps do
/// not converge.
bool solve_strains_for_wrench(const RodRhs& p, double s, rod::Side side, std::size_t piece,
                              const RodRhs::Local& loc, const Vec6& target, double scale, Vec3& e,
                              Vec3& om, SectionWrench& w) {
  for (int it = 0; it < 30; ++it) {
    section_wrench(p, s, side, piece, loc, e, om, w);
    const Vec6 F = w.W - target;
    Vec6 magnitude;
    magnitude << loc.Kn.cwiseProduct(e).cwiseAbs(), loc.Kw.cwiseProduct(om - loc.ws).cwiseAbs();
    magnitude += target.cwiseAbs();
    for (int i = 0; i < p.n_act; ++i) magnitude += std::abs(p.cT[i]) * w.u[i].cwiseAbs();
    const bool at_round_off = (F.cwiseAbs().array() <= 1e-14 * magnitude.array()).all();
    const Vec6 dz = w.M.partialPivLu().solve(F);
    if (!dz.allFinite()) return false;
    e -= dz.head<3>();
    om -= dz.tail<3>();
    if (F.cwiseAbs().maxCoeff() <= 1e-15 * scale || at_round_off ||
        dz.cwiseAbs().maxCoeff() <=
            1e-15 * (e.cwiseAbs().maxCoeff() + om.cwiseAbs().maxCoeff() * p.L + 1e-300)) {
      return true;
    }
  }
  return false;
}

}  // namespace

bool RodRhs::strain_jump(std::size_t knot, Eigen::VectorXd& Y, int directions) const {
  if (!knot_jumps[knot]) return true;
  const double s = knots[knot];
  Local left, right;
  properties(s, rod::Side::kLeft, left.Kn, left.Kw, left.ws, left.wf);
  properties(s, rod::Side::kRight, right.Kn, right.Kw, right.ws, right.wf);
  const Vec3 e_l = Y.segment<3>(kNu), om_l = Y.segment<3>(kOmega);
  SectionWrench wl, wr;
  section_wrench(*this, s, rod::Side::kLeft, knot - 1, left, e_l, om_l, wl);
  // Start from the strains of the rod's own wrench (exact without loaded strings).
  Vec3 e = wl.W.head<3>().cwiseQuotient(right.Kn);
  Vec3 om = right.ws + wl.W.tail<3>().cwiseQuotient(right.Kw);
  bool loaded = false;
  for (int i = 0; i < n_act; ++i) loaded = loaded || (cT[i] != 0.0 && runs(knot, i));
  if (loaded) {
    // Subtract the strings' share at the left strains as the start, then Newton.
    Vec6 rod_part = wl.W;
    for (int i = 0; i < n_act; ++i) {
      if (runs(knot, i)) rod_part -= cT[i] * wl.u[i];  // a string ending here: the rod's now
    }
    e = rod_part.head<3>().cwiseQuotient(right.Kn);
    om = right.ws + rod_part.tail<3>().cwiseQuotient(right.Kw);
    if (!solve_strains_for_wrench(*this, s, rod::Side::kRight, knot, right, wl.W,
                                  wl.W.cwiseAbs().maxCoeff(), e, om, wr)) {
      return false;
    }
  }
  Y.segment<3>(kNu) = e;
  Y.segment<3>(kOmega) = om;
  if (directions == 0) return Y.head(dim).allFinite();
  section_wrench(*this, s, rod::Side::kRight, knot, right, e, om, wr);
  const Eigen::PartialPivLU<Mat6> lu(wr.M);
  for (int j = 0; j < directions; ++j) {
    double* yj = Y.data() + dim * (j + 1);
    Vec6 dz_l;
    dz_l << Vec3(yj + kNu), Vec3(yj + kOmega);
    Vec6 b = wl.M * dz_l;
    for (int i = 0; i < n_act; ++i) {
      if (unknown_of[i] == j) b += count[i] * (wl.u[i] - wr.u[i]);
    }
    const Vec6 dz = lu.solve(b);
    Eigen::Map<Vec3>(yj + kNu) = dz.head<3>();
    Eigen::Map<Vec3>(yj + kOmega) = dz.tail<3>();
  }
  return Y.allFinite();
}

bool RodRhs::point_wrench_jump(double s, const Vec3& f_B, const Vec3& m_B,
                               Eigen::VectorXd& y) const {
  const Local& k = local(s);
  const Vec3 Kn = k.Kn, Kw = k.Kw;
  const rod::Side side = s < piece_mid ? rod::Side::kRight : rod::Side::kLeft;
  bool loaded = false;
  for (int i = 0; i < n_act; ++i) loaded = loaded || (cT[i] != 0.0 && runs(piece, i));
  Vec3 e = y.segment<3>(kNu), om = y.segment<3>(kOmega);
  if (!loaded) {
    // W = (K_nu e, K_omega (omega - omega*)): the jump is linear in the strains.
    y.segment<3>(kNu) = e - f_B.cwiseQuotient(Kn);
    y.segment<3>(kOmega) = om - m_B.cwiseQuotient(Kw);
    return y.head(dim).allFinite();
  }
  Local loc = k;  // local() may be overwritten by the section wrench's evaluations
  SectionWrench w;
  section_wrench(*this, s, side, piece, loc, e, om, w);
  Vec6 target = w.W;
  target.head<3>() -= f_B;
  target.tail<3>() -= m_B;
  const double scale = std::max(w.W.cwiseAbs().maxCoeff(), target.cwiseAbs().maxCoeff());
  e -= f_B.cwiseQuotient(Kn);
  om -= m_B.cwiseQuotient(Kw);
  if (!solve_strains_for_wrench(*this, s, side, piece, loc, target, scale, e, om, w)) return false;
  y.segment<3>(kNu) = e;
  y.segment<3>(kOmega) = om;
  return y.head(dim).allFinite();
}

void RodRhs::set_parameters(const rod::Loads& act, double lambda, const Eigen::VectorXd& x) {
  for (int i = 0; i < n_act; ++i) {
    const int k = unknown_of[i];
    const double T = k >= 0 ? x[k] : lambda * act.actuators[i].tension_N;
    cT[i] = count[i] * T;
    if (k >= 0) {
      const auto& tca = *model.actuators[i].drive.tca;
      rod::ramp_segments(tca.material(), act.actuators[i].segments, lambda, scaled_segments[i]);
    }
  }
  if (uniform) {
    f_ext_W = lambda * density_base * area_base * act.gravity_W_m_s2;
  } else {
    f_ext_W = lambda * rho_A_ref * act.gravity_W_m_s2;  // times weight_factor(s) in the RHS
  }
  layout->set_parameters(*this);
}

}  // namespace tcasim::cosserat::internal
