#include "cosserat/dynamics.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "cosserat/dynamics_section.hpp"
#include "cosserat/shooting.hpp"
#include "cosserat/string_system.hpp"

namespace tcasim::cosserat {

namespace {

using internal::hat;
using internal::Mat3;
using internal::Mat6;
using internal::Vec3;
using internal::Vec6;

// State layout (dynamics.hpp).
constexpr int kP = 0, kR = 3, kN = 12, kM = 15, kQ = 18, kW = 21, kDelta = 24;

/// What a stage point (or the tip point) keeps: the strains and velocities whose time
/// derivatives the BDF-alpha formula needs, e = nu - nu* (the deviation, as in the static
/// solver: no cancellation), omega, q, w, and the position p for the energies.
struct PointData {
  Vec3 e = Vec3::Zero(), omega = Vec3::Zero(), q = Vec3::Zero(), w = Vec3::Zero();
  Vec3 p = Vec3::Zero();
};
/// History (or time derivative) of the differentiated quantities at one point.
struct PointRates {
  Vec3 e = Vec3::Zero(), omega = Vec3::Zero(), q = Vec3::Zero(), w = Vec3::Zero();
};

// Classical RK4: stage nodes c and the multipliers of the previous stage.
constexpr double kStageC[4] = {0.0, 0.5, 0.5, 1.0};
constexpr double kStageA[4] = {0.0, 0.5, 0.5, 1.0};
constexpr double kStageB[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
/// Up to this many unknowns the Newton system is factorized densely (partial pivoting):
/// faster than SparseLU at that size, the same solution.
constexpr int kDenseUnknowns = 300;
/// Chord iterations with one factorization before a fresh Jacobian is computed.
constexpr int kStaleIterations = 6;

}  // namespace

const char* to_string(DynamicsSummary::Status s) {
  switch (s) {
    case DynamicsSummary::Status::kConverged:
      return "converged";
    case DynamicsSummary::Status::kMaxIterations:
      return "max-iterations";
    case DynamicsSummary::Status::kNotConverging:
      return "not-converging";
    case DynamicsSummary::Status::kSingularJacobian:
      return "singular-jacobian";
    case DynamicsSummary::Status::kNonFinite:
      return "non-finite";
    case DynamicsSummary::Status::kNotRun:
      return "not-run";
  }
  return "unknown";
}

double spatial_growth_rate(const rod::RodModel& model, const DynamicsOptions& o) {
  const dynamics::SectionAt sec = dynamics::section_at(model, 0.0, o.viscosity_Pa_s);
  const double a = o.alpha;
  const double c0 = (1.5 + a) / (o.dt_s * (1.0 + a));
  // A step turns EI w'''' = -rho A w_tt into w'''' ~ -(rho A / EI) c0^2 w, and the wave
  // equations of extension, shear and torsion into u'' ~ (rho / stiffness) c0^2 u.
  const double EI = std::min(sec.K_bt.x(), sec.K_bt.y());
  double kappa = std::pow(sec.rho_A / EI, 0.25) * std::sqrt(c0);
  kappa = std::max(kappa, std::sqrt(sec.rho_A / sec.K_se.minCoeff()) * c0);
  kappa = std::max(kappa, std::sqrt(sec.rho_J.z() / sec.K_bt.z()) * c0);
  return kappa;
}

int recommended_steps(const rod::RodModel& model, const DynamicsOptions& o) {
  const double n = std::ceil(model.length_m * spatial_growth_rate(model, o));
  const int steps = static_cast<int>(std::min(n, 100000.0));
  return std::max(20, steps + steps % 2);
}

struct RodDynamics::Impl {
  Impl(const rod::RodModel& m, const DynamicsOptions& o);

  // --- the discretization
  /// Right-hand side at arc length s of state y with the history of stage slot `slot`;
  /// the stage's strains and velocities are written to trial[slot]. With A: the Jacobian
  /// df/dy (D x D). False when the section's constitutive solve fails or y is not finite.
  bool rhs(double s, const Eigen::VectorXd& y, int slot, Eigen::VectorXd& dy, Eigen::MatrixXd* A);
  /// Integrates interval k from y (its S RK4 steps), writing the grid states; Phi: the
  /// sensitivity dy_end/dy0 (D x D) when non-null.
  bool integrate_interval(int k, Eigen::VectorXd& y, Eigen::MatrixXd* Phi);
  /// State at node k from the unknowns z.
  void node_state(const Eigen::VectorXd& z, int k, Eigen::VectorXd& y) const;
  /// Scaled residual at z; with `jacobian`, also the scaled Jacobian into J_.
  bool evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& r, bool jacobian);
  /// Tip residual rows (6) of the end state and, with G, their derivative (6 x D).
  void tip_residual(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> r,
                    Eigen::MatrixXd* G) const;
  /// Newton (chord) iterations from z.
  DynamicsSummary solve(Eigen::VectorXd& z);
  void set_loads(const rod::Loads& loads);
  void set_scales();
  int unknowns() const { return 6 + (M - 1) * D; }
  int slots() const { return 4 * N + 1; }  // 4 stages per step, then the tip point

  const rod::RodModel& model;
  DynamicsOptions opt;
  dynamics::SectionAt sec;  // uniform along s (dynamics::section_is_uniform)
  int n_act = 0, D = 0, N = 0, M = 0, S = 0;
  double L = 0.0, h = 0.0;
  // BDF-alpha: y_t(n+1) = c0 y(n+1) + c1 y(n) + c2 y(n-1) + d1 y_t(n) ([Till2019]).
  double c0 = 0.0, c1 = 0.0, c2 = 0.0, d1 = 0.0;
  double c0_active = 0.0;  // 0 for the static solve
  double t = 0.0;
  // Loads of the current solve.
  Vec3 f_ext_W = Vec3::Zero(), F_tip_W = Vec3::Zero(), M_tip_W = Vec3::Zero(), g_W = Vec3::Zero();
  std::vector<double> cT;  // count * tension per actuator
  std::vector<double> length_ratio, count;
  double F_c = 1.0;
  Eigen::VectorXd scale;  // per state component (D)
  // Per slot: history of the current step, data of the last evaluation (trial), of the
  // last two converged steps and the time derivative at the last one.
  std::vector<PointRates> hist, cur_t;
  std::vector<PointData> trial, cur, prev;
  std::vector<Eigen::VectorXd> grid;  // N + 1 states of the last evaluation
  std::vector<Eigen::VectorXd> grid_converged;
  Eigen::VectorXd z, z_prev, z_prev2;
  int history_steps = 0;  // converged steps behind z (for the extrapolated start)
  // Jacobian (scaled) and its factorization.
  Eigen::SparseMatrix<double> J_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  bool pattern_analyzed = false, lu_valid = false;
  bool dense = false;  // unknowns() <= kDenseUnknowns: dense LU instead of SparseLU
  Eigen::MatrixXd J_dense_;
  Eigen::PartialPivLU<Eigen::MatrixXd> dense_lu_;
  double lu_c0 = -1.0;
  std::vector<Eigen::Triplet<double>> triplets_;
};

RodDynamics::Impl::Impl(const rod::RodModel& m, const DynamicsOptions& o) : model(m), opt(o) {
  require(o.steps >= 1 && o.steps <= 100000, "dynamics.steps", o.steps,
          "must be an integer in [1, 100000]");
  require(o.intervals >= 0 && (o.intervals == 0 || o.steps % o.intervals == 0),
          "dynamics.intervals", o.intervals, "must be 0 (automatic) or divide steps");
  require(std::isfinite(o.dt_s) && o.dt_s > 0.0, "dynamics.dt_s", o.dt_s, "must be > 0");
  require(o.alpha >= -0.5 && o.alpha <= 0.0, "dynamics.alpha", o.alpha, "must be in [-0.5, 0]");
  require(std::isfinite(o.tolerance) && o.tolerance > 0.0, "dynamics.tolerance", o.tolerance,
          "must be > 0");
  require(o.max_iterations >= 1, "dynamics.max_iterations", o.max_iterations, "must be >= 1");
  require(std::isfinite(o.viscosity_Pa_s) && o.viscosity_Pa_s >= 0.0, "dynamics.viscosity_Pa_s",
          o.viscosity_Pa_s, "must be >= 0");
  require(std::isfinite(o.tip_mass_kg) && o.tip_mass_kg >= 0.0, "dynamics.tip_mass_kg",
          o.tip_mass_kg, "must be >= 0");
  require(std::isfinite(o.max_interval_growth) && o.max_interval_growth > 0.0,
          "dynamics.max_interval_growth", o.max_interval_growth, "must be > 0");
  if (model.tip_constraint) {
    throw DomainError("rod dynamics: a tip_constraint is not supported in dynamics yet");
  }
  n_act = static_cast<int>(model.actuators.size());
  for (const auto& a : model.actuators) {
    if (a.drive.type != rod::Drive::Type::kTension) {
      throw DomainError("rod dynamics: actuator '" + a.name +
                        "' has a TCA drive; dynamics supports tension drives only so far");
    }
    if (a.anchored_inside(model.length_m)) {
      throw DomainError("rod dynamics: actuator '" + a.name +
                        "' is anchored inside the body (span_m); dynamics supports strings from "
                        "base to tip only so far");
    }
    length_ratio.push_back(a.rest_length_m / model.length_m);
    count.push_back(static_cast<double>(a.count));
  }
  D = kDelta + n_act;
  N = o.steps;
  L = model.length_m;
  h = L / N;
  sec = dynamics::section_at(model, 0.0, o.viscosity_Pa_s);
  const double a = o.alpha, dt = o.dt_s;
  // [Till2019] BDF-alpha coefficients (their time-management code).
  c0 = (1.5 + a) / (dt * (1.0 + a));
  c1 = -2.0 / dt;
  c2 = (0.5 + a) / (dt * (1.0 + a));
  d1 = a / (1.0 + a);
  const double kappa = spatial_growth_rate(model, o);
  if (h * kappa > kMaxStepGrowth) {
    throw InputError(
        "dynamics.steps", std::to_string(N),
        "is too coarse for dt_s = " + format_value(dt) + ": h kappa = " + format_value(h * kappa) +
            " must be <= " + format_value(kMaxStepGrowth) + " (at least " +
            std::to_string(static_cast<int>(std::ceil(L * kappa / kMaxStepGrowth))) + " steps)");
  }
  if (o.intervals > 0) {
    M = o.intervals;
  } else {
    M = N;
    for (int m_try = 1; m_try <= N; ++m_try) {
      if (N % m_try == 0 && (L / m_try) * kappa <= o.max_interval_growth) {
        M = m_try;
        break;
      }
    }
  }
  S = N / M;
  dense = unknowns() <= kDenseUnknowns;
  const int n_slots = slots();
  hist.assign(n_slots, {});
  cur_t.assign(n_slots, {});
  PointData rest;
  rest.omega = sec.omega_star;
  trial.assign(n_slots, rest);
  cur = prev = trial;
  grid.assign(N + 1, Eigen::VectorXd::Zero(D));
  grid_converged = grid;
  cT.assign(n_act, 0.0);
  scale.resize(D);
}

void RodDynamics::Impl::set_loads(const rod::Loads& loads_in) {
  loads_in.validate(model);
  const rod::Loads loads = loads_in.applied(model);
  for (int i = 0; i < n_act; ++i) cT[i] = count[i] * loads.actuators[i].tension_N;
  g_W = loads.gravity_W_m_s2;
  f_ext_W = sec.rho_A * g_W;
  F_tip_W = loads.tip_force_W_N;
  M_tip_W = loads.tip_moment_W_Nm;
}

void RodDynamics::Impl::set_scales() {
  // Rates: c0 in dynamics, the first bending frequency scale sqrt(EI / (rho A L^4)) at rest.
  const double EI = std::min(sec.K_bt.x(), sec.K_bt.y());
  double rate = c0_active;
  if (sec.rho_A > 0.0) rate = std::max(rate, std::sqrt(EI / (sec.rho_A * std::pow(L, 4))));
  if (!(rate > 0.0)) rate = 1.0;
  scale.segment<3>(kP).setConstant(L);
  scale.segment<9>(kR).setConstant(1.0);
  scale.segment<3>(kN).setConstant(F_c);
  scale.segment<3>(kM).setConstant(F_c * L);
  scale.segment<3>(kQ).setConstant(L * rate);
  scale.segment<3>(kW).setConstant(rate);
  if (n_act > 0) scale.tail(n_act).setConstant(L);
}

bool RodDynamics::Impl::rhs(double s, const Eigen::VectorXd& y, int slot, Eigen::VectorXd& dy,
                            Eigen::MatrixXd* A) {
  const Eigen::Map<const Mat3> R(y.data() + kR);
  const Vec3 Nb = y.segment<3>(kN), Mb = y.segment<3>(kM);
  const Vec3 q = y.segment<3>(kQ), w = y.segment<3>(kW);
  const PointRates& H = hist[slot];
  PointData& X = trial[slot];
  const double c = c0_active;
  // Effective stiffness of the step: K + c0 B (Kelvin-Voigt, docs/conventions.md).
  const Vec3 Kt_se = sec.K_se + c * sec.B_se, Kt_bt = sec.K_bt + c * sec.B_bt;
  const Vec3 Kt_se_inv = Kt_se.cwiseInverse(), Kt_bt_inv = Kt_bt.cwiseInverse();
  // Section constitutive law solved for the strains xi = (e, omega):
  //   K_se e + B_se (c0 e + e_h) + sum c_i T_i qh_i = N,
  //   K_bt (omega - omega*) + B_bt (c0 omega + omega_h) + sum c_i T_i r_i x qh_i = M.
  const Vec3 bN = Nb - sec.B_se.cwiseProduct(H.e);
  const Vec3 bM = Mb + sec.K_bt.cwiseProduct(sec.omega_star) - sec.B_bt.cwiseProduct(H.omega);
  bool strings = false;
  for (int i = 0; i < n_act; ++i) strings = strings || cT[i] != 0.0;
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
        if (cT[i] == 0.0) continue;
        const rod::Routing& rt = model.actuators[i].routing;
        const Vec3 r = rt.r(s), dr = rt.dr(s);
        const Vec3 qi = e + Vec3::UnitZ() + om.cross(r) + dr;
        const double qn = qi.norm();
        const Vec3 qh = qi / qn;
        gN += cT[i] * qh;
        gM += cT[i] * r.cross(qh);
        sys.add(r, cT[i] / qn, qh);
        load += std::abs(cT[i]);
      }
      sys.factor();
      Vec6 dx;
      dx << gN, gM;
      const double gnorm = std::max(gN.lpNorm<Eigen::Infinity>(), gM.lpNorm<Eigen::Infinity>() / L);
      sys.solve_in_place(dx);
      e -= dx.head<3>();
      om -= dx.tail<3>();
      if (!dx.allFinite()) return false;
      done = gnorm <= 1e-15 * load ||
             dx.head<3>().lpNorm<Eigen::Infinity>() + L * dx.tail<3>().lpNorm<Eigen::Infinity>() <=
                 1e-15 * (e.lpNorm<Eigen::Infinity>() + L * om.lpNorm<Eigen::Infinity>() + 1e-300);
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
  const Vec3 Jw = sec.rho_J.cwiseProduct(w);
  // [Till2019] (body frame): p' = R nu, R' = R hat(omega),
  //   N' = -omega x N + rho A (w x q + q_t) - R^T f_ext,
  //   M' = -omega x M - nu x N + w x rho J w + rho J w_t,
  //   q' = nu_t - omega x q + w x nu,  w' = omega_t - omega x w.
  dy.segment<3>(kP) = R * nu;
  Eigen::Map<Mat3>(dy.data() + kR) = R * hat(om);
  dy.segment<3>(kN) = -om.cross(Nb) + sec.rho_A * (w.cross(q) + q_t) - R.transpose() * f_ext_W;
  dy.segment<3>(kM) = -om.cross(Mb) - nu.cross(Nb) + w.cross(Jw) + sec.rho_J.cwiseProduct(w_t);
  dy.segment<3>(kQ) = e_t - om.cross(q) + w.cross(nu);
  dy.segment<3>(kW) = om_t - om.cross(w);
  for (int i = 0; i < n_act; ++i) {
    const rod::Routing& rt = model.actuators[i].routing;
    const Vec3 qi = nu + om.cross(rt.r(s)) + rt.dr(s);
    dy[kDelta + i] = qi.norm() - length_ratio[i];
  }
  if (!A) return true;
  // Jacobian: direct part (xi fixed) plus df/dxi Z on the (N, M) columns.
  Eigen::MatrixXd& Aj = *A;
  Aj.setZero(D, D);
  const Mat3 I = Mat3::Identity();
  const Mat3 Om = hat(om);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      Aj(kP + i, kR + 3 * j + i) = nu[j];                                         // d(R nu)/dR_ij
      for (int k = 0; k < 3; ++k) Aj(kR + 3 * k + i, kR + 3 * j + i) = Om(j, k);  // R hat(om)
      Aj(kN + j, kR + 3 * j + i) = -f_ext_W[i];                                   // -R^T f
    }
  }
  Aj.block<3, 3>(kN, kN) = -Om;
  Aj.block<3, 3>(kN, kQ) = sec.rho_A * (hat(w) + c * I);
  Aj.block<3, 3>(kN, kW) = -sec.rho_A * hat(q);
  Aj.block<3, 3>(kM, kM) = -Om;
  Aj.block<3, 3>(kM, kN) = -hat(nu);
  Aj.block<3, 3>(kM, kW) =
      hat(w) * sec.rho_J.asDiagonal() - hat(Jw) + c * Mat3(sec.rho_J.asDiagonal());
  Aj.block<3, 3>(kQ, kQ) = -Om;
  Aj.block<3, 3>(kQ, kW) = -hat(nu);
  Aj.block<3, 3>(kW, kW) = -Om;
  // df/dxi (D x 6).
  Eigen::Matrix<double, Eigen::Dynamic, 6> Fx =
      Eigen::Matrix<double, Eigen::Dynamic, 6>::Zero(D, 6);
  Fx.block<3, 3>(kP, 0) = R;
  for (int j = 0; j < 3; ++j) Fx.block<3, 3>(kR + 3 * j, 3) = -R * hat(Vec3::Unit(j));
  Fx.block<3, 3>(kN, 3) = hat(Nb);
  Fx.block<3, 3>(kM, 0) = hat(Nb);
  Fx.block<3, 3>(kM, 3) = hat(Mb);
  Fx.block<3, 3>(kQ, 0) = c * I + hat(w);
  Fx.block<3, 3>(kQ, 3) = hat(q);
  Fx.block<3, 3>(kW, 3) = c * I + hat(w);
  for (int i = 0; i < n_act; ++i) {
    const rod::Routing& rt = model.actuators[i].routing;
    const Vec3 r = rt.r(s);
    const Vec3 qi = nu + om.cross(r) + rt.dr(s);
    const Vec3 qh = qi.normalized();
    Fx.block<1, 3>(kDelta + i, 0) = qh.transpose();
    Fx.block<1, 3>(kDelta + i, 3) = r.cross(qh).transpose();
  }
  Aj.middleCols<6>(kN) += Fx * Z;
  return true;
}

bool RodDynamics::Impl::integrate_interval(int k, Eigen::VectorXd& y, Eigen::MatrixXd* Phi) {
  Eigen::VectorXd Y(D), kj(D), acc(D);
  Eigen::MatrixXd A, dY, dK, dacc;
  if (Phi) {
    Phi->setIdentity(D, D);
    dY.resize(D, D);
    dK.resize(D, D);
    dacc.resize(D, D);
  }
  for (int i = k * S; i < (k + 1) * S; ++i) {
    grid[i] = y;
    const double s = i * h;
    acc.setZero();
    if (Phi) dacc.setZero();
    for (int j = 0; j < 4; ++j) {
      if (j == 0) {
        Y = y;
        if (Phi) dY = *Phi;
      } else {
        Y = y + (kStageA[j] * h) * kj;
        if (Phi) dY = *Phi + (kStageA[j] * h) * dK;
      }
      if (!rhs(s + kStageC[j] * h, Y, 4 * i + j, kj, Phi ? &A : nullptr)) return false;
      if (!std::isfinite(kj.sum())) return false;
      acc += kStageB[j] * kj;
      if (Phi) {
        dK.noalias() = A * dY;
        dacc += kStageB[j] * dK;
      }
    }
    y += h * acc;
    if (Phi) *Phi += h * dacc;
  }
  if (k == M - 1) grid[N] = y;
  return y.allFinite();
}

void RodDynamics::Impl::node_state(const Eigen::VectorXd& zz, int k, Eigen::VectorXd& y) const {
  if (k == 0) {
    y.setZero(D);
    y.segment<3>(kP) = model.base_position_W_m;
    Eigen::Map<Mat3>(y.data() + kR) = model.R_WB0;
    y.segment<6>(kN) = zz.head<6>();
    return;
  }
  y = zz.segment(6 + (k - 1) * D, D);
}

void RodDynamics::Impl::tip_residual(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> r,
                                     Eigen::MatrixXd* G) const {
  // Balance of the tip section and the tip mass m_t (docs/conventions.md):
  //   N(L) = R^T (F_e + m_t g) - m_t (q_t + w x q),   M(L) = R^T M_e.
  const Eigen::Map<const Mat3> R(y.data() + kR);
  const Vec3 q = y.segment<3>(kQ), w = y.segment<3>(kW);
  const double mt = opt.tip_mass_kg;
  const PointRates& H = hist[4 * N];
  const Vec3 F = F_tip_W + mt * g_W;
  const Vec3 q_t = c0_active * q + H.q;
  r.head<3>() = (y.segment<3>(kN) - R.transpose() * F + mt * (q_t + w.cross(q))) / F_c;
  r.tail<3>() = (y.segment<3>(kM) - R.transpose() * M_tip_W) / (F_c * L);
  if (!G) return;
  G->setZero(6, D);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      (*G)(j, kR + 3 * j + i) = -F[i] / F_c;
      (*G)(3 + j, kR + 3 * j + i) = -M_tip_W[i] / (F_c * L);
    }
  }
  G->block<3, 3>(0, kN) = Mat3::Identity() / F_c;
  G->block<3, 3>(0, kQ) = mt * (c0_active * Mat3::Identity() + hat(w)) / F_c;
  G->block<3, 3>(0, kW) = -mt * hat(q) / F_c;
  G->block<3, 3>(3, kM) = Mat3::Identity() / (F_c * L);
}

bool RodDynamics::Impl::evaluate(const Eigen::VectorXd& zz, Eigen::VectorXd& r, bool jacobian) {
  const int n = unknowns();
  r.resize(n);
  Eigen::VectorXd y(D), y_next(D);
  Eigen::MatrixXd Phi, G;
  if (jacobian) triplets_.clear();
  const Eigen::ArrayXd inv_scale = scale.array().inverse();
  for (int k = 0; k < M; ++k) {
    node_state(zz, k, y);
    if (!integrate_interval(k, y, jacobian ? &Phi : nullptr)) return false;
    const int row = k * D;  // continuity rows of node k + 1; the tip rows after the last
    const int col0 = k == 0 ? 0 : 6 + (k - 1) * D;
    // Columns of node k's unknowns: (N, M) at the base, the whole state elsewhere.
    const int first = k == 0 ? kN : 0, ncols = k == 0 ? 6 : D;
    if (k < M - 1) {
      node_state(zz, k + 1, y_next);
      r.segment(row, D) = ((y - y_next).array() * inv_scale).matrix();
      if (jacobian) {
        const int col1 = 6 + k * D;
        for (int c = 0; c < ncols; ++c) {
          for (int rr = 0; rr < D; ++rr) {
            triplets_.emplace_back(row + rr, col0 + c,
                                   Phi(rr, first + c) * scale[first + c] * inv_scale[rr]);
          }
        }
        for (int rr = 0; rr < D; ++rr) triplets_.emplace_back(row + rr, col1 + rr, -1.0);
      }
    } else {
      // The tip point's strains (energies, damping history) and the tip residual.
      Eigen::VectorXd dy(D);
      if (!rhs(L, y, 4 * N, dy, nullptr)) return false;
      tip_residual(y, r.segment<6>(row), jacobian ? &G : nullptr);
      if (jacobian) {
        const Eigen::MatrixXd GP = G * Phi;
        for (int c = 0; c < ncols; ++c) {
          for (int rr = 0; rr < 6; ++rr) {
            triplets_.emplace_back(row + rr, col0 + c, GP(rr, first + c) * scale[first + c]);
          }
        }
      }
    }
  }
  if (!r.allFinite()) return false;
  if (jacobian) {
    if (dense) {
      J_dense_.setZero(n, n);
      for (const auto& tr : triplets_) J_dense_(tr.row(), tr.col()) += tr.value();
      dense_lu_.compute(J_dense_);
      // PartialPivLU does not report singularity: check the pivots.
      const Eigen::VectorXd piv = dense_lu_.matrixLU().diagonal().cwiseAbs();
      lu_valid = piv.allFinite() && piv.minCoeff() > 1e-14 * piv.maxCoeff();
      lu_c0 = c0_active;
      return true;
    }
    J_.resize(n, n);
    J_.setFromTriplets(triplets_.begin(), triplets_.end());
    J_.makeCompressed();
    if (!pattern_analyzed) {
      lu_.analyzePattern(J_);
      pattern_analyzed = true;
    }
    lu_.factorize(J_);
    lu_valid = lu_.info() == Eigen::Success;
    lu_c0 = c0_active;
  }
  return true;
}

DynamicsSummary RodDynamics::Impl::solve(Eigen::VectorXd& zz) {
  DynamicsSummary sum;
  const int n = unknowns();
  Eigen::VectorXd unknown_scale(n);
  unknown_scale.head<6>() = scale.segment<6>(kN);
  for (int k = 1; k < M; ++k) unknown_scale.segment(6 + (k - 1) * D, D) = scale;
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

// ---------------------------------------------------------------------------

RodDynamics::RodDynamics(const rod::RodModel& model, const DynamicsOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}
RodDynamics::~RodDynamics() = default;

DynamicsSummary RodDynamics::initialize(const rod::Loads& loads) {
  Impl& d = *impl_;
  d.set_loads(loads);
  d.F_c = rod::characteristic_force_N(d.model, loads);
  d.c0_active = 0.0;
  d.t = 0.0;
  d.history_steps = 0;
  for (auto& hh : d.hist) hh = PointRates{};
  d.set_scales();
  // Start: the static shooting solver's base unknowns, integrated over the whole length with
  // this discretization (a static problem has no fast spatial modes).
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(d.D);
  y0.segment<3>(kP) = d.model.base_position_W_m;
  Eigen::Map<Mat3>(y0.data() + kR) = d.model.R_WB0;
  {
    Options so;
    so.integrator.steps = std::max(2, d.N + d.N % 2);
    ShootingSolver solver(d.model, so);
    Solution sol;
    const Summary ss = solver.solve(loads, sol);
    if (ss.converged()) {
      const Vec3 e0 = sol.unknowns.head<3>(), om0 = sol.unknowns.segment<3>(3);
      Vec3 Nb = d.sec.K_se.cwiseProduct(e0);
      Vec3 Mb = d.sec.K_bt.cwiseProduct(om0 - d.sec.omega_star);
      for (int i = 0; i < d.n_act; ++i) {
        const rod::Routing& rt = d.model.actuators[i].routing;
        const Vec3 r = rt.r(0.0);
        const Vec3 qh = (e0 + Vec3::UnitZ() + om0.cross(r) + rt.dr(0.0)).normalized();
        Nb += d.cT[i] * qh;
        Mb += d.cT[i] * r.cross(qh);
      }
      y0.segment<3>(kN) = Nb;
      y0.segment<3>(kM) = Mb;
    }
  }
  Eigen::VectorXd zz(d.unknowns());
  zz.head<6>() = y0.segment<6>(kN);
  Eigen::VectorXd y = y0;
  for (int k = 0; k < d.M - 1; ++k) {
    if (!d.integrate_interval(k, y, nullptr)) break;
    zz.segment(6 + k * d.D, d.D) = y;
  }
  DynamicsSummary sum = d.solve(zz);
  if (!sum.converged()) return sum;
  d.z = zz;
  d.z_prev = zz;
  d.z_prev2 = zz;
  d.cur = d.trial;
  d.prev = d.trial;
  for (auto& r : d.cur_t) r = PointRates{};
  d.grid_converged = d.grid;
  return sum;
}

DynamicsSummary RodDynamics::step(const rod::Loads& loads) {
  Impl& d = *impl_;
  d.set_loads(loads);
  d.c0_active = d.c0;
  d.set_scales();
  // History of the BDF-alpha formula at every slot: y_h = c1 y(n) + c2 y(n-1) + d1 y_t(n).
  for (int i = 0; i < d.slots(); ++i) {
    const PointData &a = d.cur[i], &b = d.prev[i];
    const PointRates& at = d.cur_t[i];
    PointRates& hh = d.hist[i];
    hh.e = d.c1 * a.e + d.c2 * b.e + d.d1 * at.e;
    hh.omega = d.c1 * a.omega + d.c2 * b.omega + d.d1 * at.omega;
    hh.q = d.c1 * a.q + d.c2 * b.q + d.d1 * at.q;
    hh.w = d.c1 * a.w + d.c2 * b.w + d.d1 * at.w;
    d.trial[i] = a;
  }
  // Warm start: the unknowns extrapolated from the last steps (quadratic through three).
  Eigen::VectorXd zz = d.z;
  if (d.history_steps >= 2) {
    zz = 3.0 * d.z - 3.0 * d.z_prev + d.z_prev2;
  } else if (d.history_steps == 1) {
    zz = 2.0 * d.z - d.z_prev;
  }
  DynamicsSummary sum = d.solve(zz);
  if (!sum.converged()) {
    if (d.history_steps > 0) {
      // Retry from the last solution without extrapolation.
      zz = d.z;
      for (int i = 0; i < d.slots(); ++i) d.trial[i] = d.cur[i];
      const DynamicsSummary retry = d.solve(zz);
      sum.iterations += retry.iterations;
      sum.jacobians += retry.jacobians;
      if (retry.converged()) {
        sum.status = retry.status;
        sum.residual = retry.residual;
        sum.message.clear();
      }
    }
    if (!sum.converged()) return sum;
  }
  for (int i = 0; i < d.slots(); ++i) {
    const PointData& x = d.trial[i];
    const PointRates& hh = d.hist[i];
    PointRates rt;
    rt.e = d.c0 * x.e + hh.e;
    rt.omega = d.c0 * x.omega + hh.omega;
    rt.q = d.c0 * x.q + hh.q;
    rt.w = d.c0 * x.w + hh.w;
    d.prev[i] = d.cur[i];
    d.cur[i] = x;
    d.cur_t[i] = rt;
  }
  d.z_prev2 = d.z_prev;
  d.z_prev = d.z;
  d.z = zz;
  ++d.history_steps;
  d.grid_converged = d.grid;
  d.t += d.opt.dt_s;
  return sum;
}

double RodDynamics::time_s() const { return impl_->t; }
int RodDynamics::intervals() const { return impl_->M; }
int RodDynamics::state_dimension() const { return impl_->D; }
const std::vector<Eigen::VectorXd>& RodDynamics::grid_states() const {
  return impl_->grid_converged;
}
Eigen::Vector3d RodDynamics::tip_position_W_m() const {
  return impl_->grid_converged.back().segment<3>(kP);
}
Eigen::Matrix3d RodDynamics::tip_rotation_W() const {
  return Eigen::Map<const Mat3>(impl_->grid_converged.back().data() + kR);
}

double RodDynamics::kinetic_energy_J() const {
  const Impl& d = *impl_;
  // RK4's weights over each step's stages: the same order in s as the states.
  double T = 0.0;
  for (int i = 0; i < d.N; ++i) {
    for (int j = 0; j < 4; ++j) {
      const PointData& x = d.cur[4 * i + j];
      T += kStageB[j] * d.h * 0.5 *
           (d.sec.rho_A * x.q.squaredNorm() + x.w.dot(d.sec.rho_J.cwiseProduct(x.w)));
    }
  }
  return T + 0.5 * d.opt.tip_mass_kg * d.cur[4 * d.N].q.squaredNorm();
}

double RodDynamics::potential_energy_J() const {
  const Impl& d = *impl_;
  double U = 0.0;
  for (int i = 0; i < d.N; ++i) {
    for (int j = 0; j < 4; ++j) {
      const PointData& x = d.cur[4 * i + j];
      const Vec3 dom = x.omega - d.sec.omega_star;
      U += kStageB[j] * d.h *
           (0.5 * x.e.dot(d.sec.K_se.cwiseProduct(x.e)) +
            0.5 * dom.dot(d.sec.K_bt.cwiseProduct(dom)) - d.f_ext_W.dot(x.p));
    }
  }
  const Eigen::VectorXd& tip = d.grid_converged.back();
  U -= (d.F_tip_W + d.opt.tip_mass_kg * d.g_W).dot(tip.segment<3>(kP));
  for (int i = 0; i < d.n_act; ++i) U += d.cT[i] * tip[kDelta + i];
  return U;
}

std::vector<double> RodDynamics::tensions_N() const {
  std::vector<double> t(impl_->n_act);
  for (int i = 0; i < impl_->n_act; ++i) t[i] = impl_->cT[i] / impl_->count[i];
  return t;
}

std::vector<double> RodDynamics::elongations_m() const {
  std::vector<double> e(impl_->n_act);
  for (int i = 0; i < impl_->n_act; ++i) e[i] = impl_->grid_converged.back()[kDelta + i];
  return e;
}

}  // namespace tcasim::cosserat
