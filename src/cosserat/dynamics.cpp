// Rod dynamics (cosserat/dynamics.hpp): options and setup, the loads and scales of a solve,
// the static initialization and the time steps (BDF-alpha history, warm start).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "common/so3.hpp"
#include "cosserat/internal/dynamics_impl.hpp"
#include "cosserat/shooting.hpp"
#include "rod/probes.hpp"

namespace tcasim::cosserat {

using namespace dynamics_names;

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

namespace {

/// kappa of one section (spatial_growth_rate) for the BDF-alpha coefficient c0.
double growth_rate_of(const dynamics::SectionAt& sec, double c0) {
  // A step turns EI w = -rho A w_tt into w ~ -(rho A / EI) c0^2 w, and the wave
  // equations of extension, shear and torsion into u'' ~ (rho / stiffness) c0^2 u.
  const double EI = std::min(sec.K_bt.x(), sec.K_bt.y());
  double kappa = std::pow(sec.rho_A / EI, 0.25) * std::sqrt(c0);
  kappa = std::max(kappa, std::sqrt(sec.rho_A / sec.K_se.minCoeff()) * c0);
  kappa = std::max(kappa, std::sqrt(sec.rho_J.z() / sec.K_bt.z()) * c0);
  return kappa;
}

/// BDF-alpha coefficients z_t(n+1) = c0 z(n+1) + c1 z(n) + c2 z(n-1) + d1 z_t(n).
struct BdfAlpha {
  double c0, c1, c2, d1;
};

/// The coefficients of a step of size dt after one of size k.
BdfAlpha bdf_alpha(double a, double dt, double k) {
  BdfAlpha b;
  if (k == dt) {
    // [Till2019] BDF-alpha coefficients (their time-management code).
    b.c0 = (1.5 + a) / (dt * (1.0 + a));
    b.c1 = -2.0 / dt;
    b.c2 = (0.5 + a) / (dt * (1.0 + a));
    b.d1 = a / (1.0 + a);
    return b;
  }
  // Variable steps (docs/conventions.md "Variable time steps (shooting)"): d1 as at constant
  // steps, c1 and c2 from exactness for t and t^2 with z(n) at t - dt, z(n-1) at t - dt - k;
  // c0 = -(c1 + c2) keeps c0 + c1 + c2 = 0 (a static equilibrium stays a fixed point).
  b.d1 = a / (1.0 + a);
  b.c1 = -(1.0 - b.d1) / dt - (1.0 + b.d1) / k;
  b.c2 = (1.0 + b.d1) * dt / (k * (dt + k));
  b.c0 = -(b.c1 + b.c2);
  return b;
}

/// Local truncation error of that step from an exact history, C_c z_ttt (Taylor at t(n+1):
/// the formula errs by tau = C_tau z_ttt, the step by -tau / c0).
double truncation_constant(const BdfAlpha& b, double dt, double k) {
  const double C_tau =
      -b.c1 * dt * dt * dt / 6.0 - b.c2 * std::pow(dt + k, 3) / 6.0 + b.d1 * dt * dt / 2.0;
  return -C_tau / b.c0;
}

}  // namespace

double spatial_growth_rate(const rod::RodModel& model, const DynamicsOptions& o) {
  const double a = o.alpha;
  const double c0 = (1.5 + a) / (o.dt_s * (1.0 + a));
  double kappa = growth_rate_of(dynamics::section_at(model, 0.0, o.viscosity_Pa_s), c0);
  if (model.uniform_body()) return kappa;
  // A varying body: the largest rate at the ends and breakpoints (both sides) and at 8 points
  // inside each piece (the rates vary smoothly there).
  std::vector<double> knots = model.breakpoints();
  knots.insert(knots.begin(), 0.0);
  knots.push_back(model.length_m);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    for (int j = 0; j <= 8; ++j) {
      const double s = knots[k] + (knots[k + 1] - knots[k]) * j / 8.0;
      for (const rod::Side side : {rod::Side::kLeft, rod::Side::kRight}) {
        kappa = std::max(
            kappa, growth_rate_of(dynamics::section_at(model, s, o.viscosity_Pa_s, side), c0));
      }
    }
  }
  return kappa;
}

int recommended_steps(const rod::RodModel& model, const DynamicsOptions& o) {
  const double n = std::ceil(model.length_m * spatial_growth_rate(model, o));
  const int steps = static_cast<int>(std::min(n, static_cast<double>(ode::kMaxFixedSteps)));
  return std::max(20, steps + steps % 2);
}

RodDynamics::Impl::Impl(const rod::RodModel& m, const DynamicsOptions& o) : model(m), opt(o) {
  require(o.steps >= 1 && o.steps <= ode::kMaxFixedSteps, "dynamics.steps", o.steps,
          fmt::format("must be an integer in [1, {}]", ode::kMaxFixedSteps));
  require(o.intervals >= 0 && (o.intervals == 0 || o.steps % o.intervals == 0),
          "dynamics.intervals", o.intervals, "must be 0 (automatic) or divide steps");
  require(std::isfinite(o.dt_s) && o.dt_s > 0.0, "dynamics.dt_s", o.dt_s, "must be > 0");
  require(o.alpha >= -0.5 && o.alpha <= 0.0, "dynamics.alpha", o.alpha, "must be in [-0.5, 0]");
  require(std::isfinite(o.tolerance) && o.tolerance > 0.0, "dynamics.tolerance", o.tolerance,
          "must be > 0");
  require(o.max_iterations >= 1, "dynamics.max_iterations", o.max_iterations, "must be >= 1");
  if (o.viscosity_Pa_s) {
    require(std::isfinite(*o.viscosity_Pa_s) && *o.viscosity_Pa_s >= 0.0, "dynamics.viscosity_Pa_s",
            *o.viscosity_Pa_s, "must be >= 0");
  }
  if (o.tip_mass_kg) {
    require(std::isfinite(*o.tip_mass_kg) && *o.tip_mass_kg >= 0.0, "dynamics.tip_mass_kg",
            *o.tip_mass_kg, "must be >= 0");
  }
  require(std::isfinite(o.max_interval_growth) && o.max_interval_growth > 0.0,
          "dynamics.max_interval_growth", o.max_interval_growth, "must be > 0");
  if (model.tip_constraint) {
    throw DomainError("rod dynamics: a tip_constraint is not supported in dynamics yet");
  }
  n_act = static_cast<int>(model.actuators.size());
  tca_slot.assign(n_act, -1);
  segments.resize(n_act);
  temperatures_K.resize(n_act);
  for (int i = 0; i < n_act; ++i) {
    const rod::Actuator& a = model.actuators[i];
    if (a.drive.type == rod::Drive::Type::kTca) {
      tca_slot[i] = n_tca++;
      tca_actuator.push_back(i);
    }
    // The rest length per unit length of the span (the string's elongation integrates over
    // its span only).
    length_ratio.push_back(a.rest_length_m / (a.span_end_m(model.length_m) - a.span_start_m()));
    count.push_back(static_cast<double>(a.count));
  }
  if (n_tca > kMaxTcas) {
    throw DomainError("rod dynamics: " + std::to_string(n_tca) + " TCA-driven actuators; at most " +
                      std::to_string(kMaxTcas) + " are supported");
  }
  kT = kDelta + n_act;
  D = kT + n_tca;
  tip_mass_kg = o.tip_mass_kg.value_or(model.tip_mass_kg);
  L = model.length_m;
  uniform = dynamics::section_is_uniform(model, o.viscosity_Pa_s);
  // Probes are reported at grid nodes (docs/scenario-format.md "Probes and frames"): a probe
  // between the nodes of the uniform grid gets a node of its own, as a breakpoint does (the
  // shooting state between nodes depends on the history there, which only nodes have).
  std::vector<double> probe_knots;
  for (const rod::Probe& p : model.probes) {
    if (p.s_m <= 0.0 || p.s_m >= L) continue;
    const double i = p.s_m / L * o.steps;
    if (!uniform || std::abs(i - std::round(i)) > 1e-9 * o.steps) probe_knots.push_back(p.s_m);
  }
  if (!probe_knots.empty()) uniform = false;
  // Anchors inside the body and spline knots are nodes too.
  std::vector<double> string_knot_s = model.anchor_points();
  for (const double s : model.routing_knots()) string_knot_s.push_back(s);
  string_knots = !string_knot_s.empty();
  if (string_knots) uniform = false;
  if (uniform) {
    N = o.steps;
    h = L / N;
    s_grid.resize(N + 1);
    for (int i = 0; i <= N; ++i) s_grid[i] = i * h;
  } else {
    // A node at every breakpoint; each piece between them in equal steps of at most L / N.
    std::vector<double> knots = dynamics::grid_breakpoints(model, o.viscosity_Pa_s);
    knots.insert(knots.end(), probe_knots.begin(), probe_knots.end());
    knots.insert(knots.end(), string_knot_s.begin(), string_knot_s.end());
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
    knots.insert(knots.begin(), 0.0);
    knots.push_back(L);
    s_grid.assign(1, 0.0);
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
      const double a = knots[k], b = knots[k + 1];
      const int n = std::max(1, static_cast<int>(std::ceil((b - a) * o.steps / L * (1.0 - 1e-12))));
      for (int j = 1; j < n; ++j) s_grid.push_back(a + (b - a) * j / n);
      s_grid.push_back(b);
    }
    N = static_cast<int>(s_grid.size()) - 1;
    h = L / o.steps;
    require(o.intervals == 0 || N % o.intervals == 0, "dynamics.intervals", o.intervals,
            "must be 0 (automatic) or divide the " + std::to_string(N) +
                " steps of this body's grid (a node at each breakpoint of its profiles)");
  }
  if (string_knots) {
    // Every anchor is a node, so a string runs along a whole step or not at all.
    step_runs.assign(N, std::vector<char>(n_act, 0));
    for (int i = 0; i < N; ++i) {
      const double mid = 0.5 * (s_grid[i] + s_grid[i + 1]);
      for (int j = 0; j < n_act; ++j) {
        const rod::Actuator& act = model.actuators[j];
        step_runs[i][j] = act.span_start_m() < mid && mid < act.span_end_m(L);
      }
    }
  }
  sec = dynamics::section_at(model, 0.0, o.viscosity_Pa_s);
  const double dt = o.dt_s;
  set_step_coefficients(dt, dt);
  const double kappa = spatial_growth_rate(model, o);
  if (h * kappa > kMaxStepGrowth) {
    throw InputError(
        "dynamics.steps", std::to_string(N),
        "is too coarse for dt_s = " + format_value(dt) + ": h kappa = " + format_value(h * kappa) +
            " must be <= " + format_value(kMaxStepGrowth) + " (at least " +
            std::to_string(static_cast<int>(std::ceil(L * kappa / kMaxStepGrowth))) + " steps)");
  }
  M = o.intervals > 0 ? o.intervals : automatic_intervals(kappa);
  S = N / M;
  if (!uniform) {
    // Stage slots 4 i + j at s_i + c_j h_i; the end stage and the tip take the left limit.
    slot_sec.resize(slots());
    for (int i = 0; i < N; ++i) {
      const double hi = s_grid[i + 1] - s_grid[i];
      for (int j = 0; j < 4; ++j) {
        const rod::Side side = j == 3 ? rod::Side::kLeft : rod::Side::kRight;
        const double s = j == 3 ? s_grid[i + 1] : s_grid[i] + kStageC[j] * hi;
        slot_sec[4 * i + j] = dynamics::section_at(model, s, o.viscosity_Pa_s, side);
      }
    }
    slot_sec[4 * N] = dynamics::section_at(model, L, o.viscosity_Pa_s, rod::Side::kLeft);
  }
  if (o.scheme == DynamicsOptions::SpatialScheme::kEuler) {
    stages = 1;
    stage_b = kEulerB;
  }
  dense = unknowns() <= kDenseUnknowns;
  const int n_slots = slots();
  hist.assign(n_slots, {});
  cur_t.assign(n_slots, {});
  trial.assign(n_slots, PointData{});
  for (int i = 0; i < n_slots; ++i) trial[i].omega = section_of(i).omega_star;
  cur = prev = trial;
  grid.assign(N + 1, Eigen::VectorXd::Zero(D));
  grid_converged = grid;
  cT.assign(n_act, 0.0);
  scale.resize(D);
  for (Eigen::VectorXd* v : {&ws_y_, &ws_dy_, &ws_stage_, &ws_k_, &ws_acc_, &ws_node_, &ws_next_}) {
    v->setZero(D);
  }
  slot_r_.resize(static_cast<std::size_t>(n_slots) * n_act);
  slot_dr_.resize(slot_r_.size());
  for (int slot = 0; slot < n_slots; ++slot) {
    // The arc length at which integrate_interval() evaluates the slot (the tip: L).
    const int i = slot / 4, j = slot % 4;
    const double s = slot == 4 * N ? L : s_grid[i] + kStageC[j] * step_length(i);
    // As rhs() reads them: at a node exactly and on the slot's side of a string knot.
    const double s_r = routing_s(slot, s);
    const rod::Side side = routing_side(slot);
    for (int act = 0; act < n_act; ++act) {
      slot_r_[slot * n_act + act] = model.actuators[act].routing.r(s_r, side);
      slot_dr_[slot * n_act + act] = model.actuators[act].routing.dr(s_r, side);
    }
  }
}

int RodDynamics::Impl::automatic_intervals(double kappa) const {
  for (int m_try = 1; m_try <= N; ++m_try) {
    if (N % m_try != 0) continue;
    double longest = L / m_try;
    if (!uniform) {
      longest = 0.0;
      const int s_try = N / m_try;
      for (int k = 0; k < m_try; ++k) {
        longest = std::max(longest, s_grid[(k + 1) * s_try] - s_grid[k * s_try]);
      }
    }
    if (longest * kappa <= opt.max_interval_growth) return m_try;
  }
  return N;
}

double RodDynamics::Impl::longest_interval() const {
  double longest = 0.0;
  for (int k = 0; k < M; ++k) longest = std::max(longest, s_grid[(k + 1) * S] - s_grid[k * S]);
  return longest;
}

void RodDynamics::Impl::set_step_coefficients(double dt, double k) {
  const BdfAlpha b = bdf_alpha(opt.alpha, dt, k);
  c0 = b.c0;
  c1 = b.c1;
  c2 = b.c2;
  d1 = b.d1;
}

void RodDynamics::Impl::set_intervals(int m) {
  M = m;
  S = N / M;
  dense = unknowns() <= kDenseUnknowns;
  pattern_analyzed = false;
  lu_valid = false;
  // The unknowns of the converged solution in the new layout; the extrapolated start begins
  // again from it (its differences are of the old layout).
  z.resize(unknowns());
  const Eigen::VectorXd& y0 = grid_converged[0];
  z.head<6>() = y0.segment<6>(kN);
  for (int j = 0; j < n_tca; ++j) z[6 + j] = y0[kT + j];
  for (int k = 1; k < M; ++k) z.segment(n0() + (k - 1) * D, D) = grid_converged[k * S];
  z_diff.assign(1, z);
  predictor_order = 0;
}

double RodDynamics::Impl::local_error_estimate() const {
  // docs/conventions.md "Variable time steps (shooting)": the step adds to the error of the
  // numerical solution its truncation error C_c z_ttt plus zeta = c2 / c0 times the error
  // trend of the history, z(n) - z(n-1) (the formula carries it on), taken as the previous
  // step's at its steady state, C_c' z_ttt / (1 - zeta'). z_ttt is the third divided difference
  // of the last four solutions: the miss of the quadratic extrapolation, C_p z_ttt with
  // C_p = -dt (dt + k) (dt + k + k2) / 6 (smooth errors of the history cancel in it).
  const double dt = est.dt[0], k = est.dt[1], k2 = est.dt[2];
  const BdfAlpha now = bdf_alpha(opt.alpha, dt, k), before = bdf_alpha(opt.alpha, k, k2);
  const double zeta = now.c2 / now.c0, zeta_before = before.c2 / before.c0;
  const double C_eff = truncation_constant(now, dt, k) +
                       zeta * truncation_constant(before, k, k2) / (1.0 - zeta_before);
  const double C_p = -dt * (dt + k) * (dt + k + k2) / 6.0;
  const double factor = C_eff / -C_p;
  // Lagrange weights of the extrapolation to t(n+1) from t(n), t(n) - k, t(n) - k - k2.
  const double l0 = (dt + k) * (dt + k + k2) / (k * (k + k2));
  const double l1 = -dt * (dt + k + k2) / (k * k2);
  const double l2 = dt * (dt + k) / ((k + k2) * k2);
  double err = 0.0;
  for (int i = 1; i <= N; ++i) {
    const Eigen::VectorXd& y_new = grid_converged[i];
    const Eigen::Matrix<double, 12, 1>&yn = node_hist[0][i], &a1 = node_hist[1][i],
                                    &a2 = node_hist[2][i];
    const Vec3 p_pred = l0 * yn.head<3>() + l1 * a1.head<3>() + l2 * a2.head<3>();
    const Vec3 e_p = factor * (y_new.segment<3>(kP) - p_pred);
    // Rotations relative to R(n), extrapolated as rotation vectors (theta(n) = 0).
    const Mat3 Rn_T = Eigen::Map<const Mat3>(yn.data() + 3).transpose();
    const Vec3 th1 = so3::log(Rn_T * Eigen::Map<const Mat3>(a1.data() + 3));
    const Vec3 th2 = so3::log(Rn_T * Eigen::Map<const Mat3>(a2.data() + 3));
    const Vec3 th_new = so3::log(Rn_T * Eigen::Map<const Mat3>(y_new.data() + kR));
    const Vec3 e_th = factor * (th_new - (l1 * th1 + l2 * th2));
    err = std::max({err, e_p.norm(), L * e_th.norm()});
  }
  return err;
}

void RodDynamics::Impl::save_snapshot() {
  snap.valid = true;
  snap.t = t;
  snap.dt_last[0] = dt_last[0];
  snap.dt_last[1] = dt_last[1];
  snap.local_error = local_error;
  snap.local_error_done = local_error_done;
  snap.est = est;
  snap.temperatures_K = temperatures_K;
  snap.segments = segments;
  snap.cT = cT;
  snap.f_ext_W = f_ext_W;
  snap.F_tip_W = F_tip_W;
  snap.M_tip_W = M_tip_W;
  snap.g_W = g_W;
  snap.cur = cur;
  snap.prev = prev;
  snap.cur_t = cur_t;
  snap.z = z;
  snap.z_diff = z_diff;
  snap.grid_converged = grid_converged;
  for (int j = 0; j < 3; ++j) snap.node_hist[j] = node_hist[j];
  snap.history_steps = history_steps;
  snap.predictor_order = predictor_order;
  snap.M = M;
  snap.lu_pending = true;
  snap.lu_saved = false;
}

void RodDynamics::Impl::set_loads(const rod::Loads& loads_in) {
  loads_in.validate(model);
  // applied(): the loads themselves at load scale 1 (no copy per time step).
  rod::Loads scaled;
  if (loads_in.load_scale != 1.0) scaled = loads_in.applied(model);
  const rod::Loads& loads = loads_in.load_scale != 1.0 ? scaled : loads_in;
  for (int i = 0; i < n_act; ++i) {
    if (tca_slot[i] >= 0) {
      // TCA: the segments' temperatures (an electric drive's are the thermal states).
      segments[i] = loads.actuators[i].segments;
      if (model.actuators[i].drive.is_electric() && !temperatures_K[i].empty()) {
        for (std::size_t k = 0; k < segments[i].size(); ++k) {
          segments[i][k].temperature_K = temperatures_K[i][k];
        }
      }
      cT[i] = 0.0;  // the tension is a state
    } else {
      cT[i] = count[i] * loads.actuators[i].tension_N;
    }
  }
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
  if (n_act > 0) scale.segment(kDelta, n_act).setConstant(L);
  if (n_tca > 0) scale.segment(kT, n_tca).setConstant(F_c);
  inv_scale_ = scale.array().inverse();
  unknown_scale(scale_z_);
  inv_scale_z_ = scale_z_.array().inverse();
}

void RodDynamics::Impl::set_section_constants() {
  const double c = c0_active;
  const auto constants = [&](const dynamics::SectionAt& sp) {
    dynamics::SectionConstants k;
    k.Kt_se_inv = (sp.K_se + c * sp.B_se).cwiseInverse();
    k.Kt_bt_inv = (sp.K_bt + c * sp.B_bt).cwiseInverse();
    k.K_bt_omega_star = sp.K_bt.cwiseProduct(sp.omega_star);
    k.f_W = sp.rho_A * g_W;
    return k;
  };
  if (uniform) {
    sec_c = constants(sec);
    return;
  }
  slot_sec_c.resize(slot_sec.size());
  for (std::size_t i = 0; i < slot_sec.size(); ++i) slot_sec_c[i] = constants(slot_sec[i]);
}

void RodDynamics::Impl::predict(int p, Eigen::VectorXd& out) const {
  // Newton's backward-difference extrapolation one step ahead: z(n+1) ~ sum_{j=0..p} nabla^j z.
  out = z_diff[0];
  for (int j = 1; j <= p; ++j) out += z_diff[j];
}

int RodDynamics::Impl::best_predictor_order(const Eigen::VectorXd& z_new) {
  // predict(p) order by order: its partial sums.
  Eigen::VectorXd& e = ws_predict_;
  int best = 0;
  double best_error = HUGE_VAL;
  const int p_max = std::min<int>(kMaxPredictorOrder, static_cast<int>(z_diff.size()) - 1);
  for (int p = 0; p <= p_max; ++p) {
    if (p == 0) {
      e = z_diff[0];
    } else {
      e += z_diff[p];
    }
    const double err = ((e - z_new).array() * inv_scale_z_).abs().maxCoeff();
    if (err < best_error) {
      best_error = err;
      best = p;
    }
  }
  return best;
}

void RodDynamics::Impl::push_difference(const Eigen::VectorXd& z_new) {
  // nabla^0 z_new = z_new, nabla^(j+1) z_new = nabla^j z_new - nabla^j z (the old table).
  Eigen::VectorXd &carry = ws_carry_, &next = ws_next_diff_;
  carry = z_new;
  for (std::size_t j = 0; j < z_diff.size(); ++j) {
    next = carry - z_diff[j];
    z_diff[j].swap(carry);  // the new nabla^j; carry: the old one (not needed any more)
    carry.swap(next);
  }
  if (static_cast<int>(z_diff.size()) <= kMaxPredictorOrder) z_diff.push_back(carry);
}

RodDynamics::RodDynamics(const rod::RodModel& model, const DynamicsOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}
RodDynamics::~RodDynamics() = default;

DynamicsSummary RodDynamics::initialize(const rod::Loads& loads) {
  Impl& d = *impl_;
  // Electric drives: the thermal states start at the loads' temperatures (the steady
  // temperatures of the inputs at t = 0 for Loads::from_model).
  for (int i = 0; i < d.n_act; ++i) {
    d.temperatures_K[i].clear();
    if (d.tca_slot[i] < 0 || !d.model.actuators[i].drive.is_electric()) continue;
    for (const tca::Segment& sg : loads.actuators.at(i).segments) {
      d.temperatures_K[i].push_back(sg.temperature_K);
    }
  }
  d.set_loads(loads);
  d.F_c = rod::characteristic_force_N(d.model, loads);
  d.c0_active = 0.0;
  d.t = 0.0;
  d.history_steps = 0;
  for (auto& hh : d.hist) hh = PointRates{};
  d.set_scales();
  d.set_section_constants();
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
        if (d.tca_slot[i] >= 0) y0[d.kT + d.tca_slot[i]] = sol.tensions_N[i];
        if (!d.runs(0, i)) continue;  // starts inside the body: no share of the base wrench
        const Vec3 r = rt.r(0.0);
        const Vec3 qh = (e0 + Vec3::UnitZ() + om0.cross(r) + rt.dr(0.0)).normalized();
        double cTi = d.cT[i];
        if (d.tca_slot[i] >= 0) cTi = d.count[i] * sol.tensions_N[i];
        Nb += cTi * qh;
        Mb += cTi * r.cross(qh);
      }
      y0.segment<3>(kN) = Nb;
      y0.segment<3>(kM) = Mb;
    }
  }
  Eigen::VectorXd zz(d.unknowns());
  zz.head<6>() = y0.segment<6>(kN);
  for (int j = 0; j < d.n_tca; ++j) zz[6 + j] = y0[d.kT + j];
  Eigen::VectorXd y = y0;
  for (int k = 0; k < d.M - 1; ++k) {
    if (!d.integrate_interval(k, y, nullptr)) break;
    zz.segment(d.n0() + k * d.D, d.D) = y;
  }
  DynamicsSummary sum = d.solve(zz);
  if (!sum.converged()) return sum;
  d.z = zz;
  d.z_diff.assign(1, zz);
  d.predictor_order = 0;
  d.cur = d.trial;
  d.prev = d.trial;
  for (auto& r : d.cur_t) r = PointRates{};
  d.grid_converged = d.grid;
  d.dt_last[0] = d.dt_last[1] = 0.0;
  d.est.stepped = false;
  d.local_error = 0.0;
  d.local_error_done = true;
  d.node_hist[0].resize(d.grid.size());
  for (std::size_t i = 0; i < d.grid.size(); ++i) d.node_hist[0][i] = d.grid[i].head<12>();
  d.node_hist[1] = d.node_hist[2] = d.node_hist[0];
  d.snap.valid = false;
  d.snap.lu_pending = false;
  return sum;
}

DynamicsSummary RodDynamics::step(const rod::Loads& loads) {
  Impl& d = *impl_;
  d.save_snapshot();
  // Electric drives: each segment's temperature over [t, t + dt] (it does not depend on the
  // mechanics, so it is advanced first, exactly where the law is linear in T, else by the
  // trapezoidal rule; docs/conventions.md "TCAs in rod dynamics").
  std::vector<std::vector<double>>& T_old = d.T_old_;
  T_old = d.temperatures_K;
  for (int i = 0; i < d.n_act; ++i) {
    if (d.temperatures_K[i].empty()) continue;
    const rod::Drive& drive = d.model.actuators[i].drive;
    for (std::size_t k = 0; k < d.temperatures_K[i].size(); ++k) {
      const rod::ElectricSegment& es = drive.electric[k];
      const bool linear = es.input != tca::ElectricInput::kVoltage ||
                          es.thermal.resistance_temperature_coefficient_1_K == 0.0;
      const tca::ThermalStep ts =
          tca::thermal_step(es.thermal, es.input, es.value.right_limit(d.t),
                            es.value.value(d.t + d.opt.dt_s), d.temperatures_K[i][k], d.opt.dt_s,
                            linear ? tca::ThermalScheme::kExact : tca::ThermalScheme::kTrapezoidal);
      if (!ts.converged) {
        d.temperatures_K = T_old;
        DynamicsSummary fail;
        fail.status = DynamicsSummary::Status::kNonFinite;
        fail.message = "the thermal step of actuator '" + d.model.actuators[i].name + "' segment " +
                       std::to_string(k) + " failed: " + ts.message;
        return fail;
      }
      d.temperatures_K[i][k] = ts.temperature_K;
    }
  }
  d.set_loads(loads);
  // The previous step's size (the first step starts from rest: any size, take this one's).
  d.set_step_coefficients(d.opt.dt_s, d.dt_last[0] > 0.0 ? d.dt_last[0] : d.opt.dt_s);
  d.c0_active = d.c0;
  d.set_scales();
  d.set_section_constants();
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
  // Warm start: the unknowns extrapolated from the last steps, by the polynomial whose order
  // would have predicted the last step best (quadratic on the first steps).
  int order = std::min(d.history_steps, d.history_steps < 3 ? 2 : d.predictor_order);
  order = std::min(order, static_cast<int>(d.z_diff.size()) - 1);  // fewer after set_intervals
  Eigen::VectorXd& zz = d.z_start_;
  const double ratio = d.dt_last[0] > 0.0 ? d.opt.dt_s / d.dt_last[0] : 1.0;
  if (ratio != 1.0) {
    // The differences are of equally spaced solutions: after a change of the step size, the
    // line through the last two, z + ratio nabla z (a start only: any is correct).
    zz = d.z_diff[0];
    if (order >= 1) zz += ratio * d.z_diff[1];
  } else {
    d.predict(order, zz);
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
    if (!sum.converged()) {
      d.temperatures_K = T_old;
      return sum;
    }
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
  d.predictor_order = d.best_predictor_order(zz);
  d.push_difference(zz);
  d.z.swap(zz);
  ++d.history_steps;
  // The estimate's data (the rest state stands for missing history, at this step's size).
  d.est.stepped = true;
  d.est.dt[0] = d.opt.dt_s;
  d.est.dt[1] = d.dt_last[0] > 0.0 ? d.dt_last[0] : d.opt.dt_s;
  d.est.dt[2] = d.dt_last[1] > 0.0 ? d.dt_last[1] : d.est.dt[1];
  d.local_error_done = false;
  d.node_hist[2].swap(d.node_hist[1]);
  d.node_hist[1].swap(d.node_hist[0]);
  for (int i = 0; i <= d.N; ++i) d.node_hist[0][i] = d.grid_converged[i].head<12>();
  d.grid_converged = d.grid;
  d.dt_last[1] = d.dt_last[0];
  d.dt_last[0] = d.opt.dt_s;
  d.t += d.opt.dt_s;
  return sum;
}

void RodDynamics::set_time_step(double dt_s) {
  Impl& d = *impl_;
  require(std::isfinite(dt_s) && dt_s > 0.0, "dynamics.dt_s", dt_s, "must be > 0");
  if (dt_s == d.opt.dt_s) return;  // checked already (an adaptive loop sets it every step)
  DynamicsOptions o = d.opt;
  o.dt_s = dt_s;
  // The grid along s stays; it must still resolve the step's fast spatial modes (as in the
  // constructor, with the constant-step c0 of dt_s).
  const double kappa = spatial_growth_rate(d.model, o);
  if (d.h * kappa > kMaxStepGrowth) {
    throw InputError("dynamics.dt_s", format_value(dt_s),
                     "is too small for the grid of " + std::to_string(d.N) +
                         " steps along s: h kappa = " + format_value(d.h * kappa) + " must be <= " +
                         format_value(kMaxStepGrowth) + " (construct with more steps)");
  }
  d.opt.dt_s = dt_s;
  // Automatic intervals: more when the shorter step's modes grow too fast across them.
  if (d.opt.intervals == 0 && d.longest_interval() * kappa > d.opt.max_interval_growth) {
    d.set_intervals(d.automatic_intervals(kappa));
  }
}

double RodDynamics::local_error_m() const {
  const Impl& d = *impl_;
  if (!d.est.stepped) return 0.0;
  if (!d.local_error_done) {
    d.local_error = d.local_error_estimate();
    d.local_error_done = true;
  }
  return d.local_error;
}

int RodDynamics::error_order() const { return 2; }

double RodDynamics::min_time_step_s() const {
  const Impl& d = *impl_;
  DynamicsOptions o = d.opt;
  auto resolved = [&](double dt) {
    o.dt_s = dt;
    return d.h * spatial_growth_rate(d.model, o) <= kMaxStepGrowth;
  };
  // kappa falls monotonically with dt: bisection in log dt between a step the grid resolves
  // (the current one, or larger) and one it does not.
  double hi = d.opt.dt_s;
  while (!resolved(hi)) hi *= 2.0;
  double lo = hi;
  for (int k = 0; k < 200 && resolved(lo); ++k) lo *= 0.5;
  if (resolved(lo)) return lo;  // resolves any step (no fast mode)
  for (int k = 0; k < 60; ++k) {
    const double mid = std::sqrt(lo * hi);
    (resolved(mid) ? hi : lo) = mid;
  }
  return hi;
}

void RodDynamics::undo_step() {
  Impl& d = *impl_;
  Impl::Snapshot& s = d.snap;
  if (!s.valid) return;
  s.valid = false;
  s.lu_pending = false;
  d.t = s.t;
  d.dt_last[0] = s.dt_last[0];
  d.dt_last[1] = s.dt_last[1];
  d.local_error = s.local_error;
  d.local_error_done = s.local_error_done;
  d.est = s.est;
  d.temperatures_K = s.temperatures_K;
  d.segments = s.segments;
  d.cT = s.cT;
  d.f_ext_W = s.f_ext_W;
  d.F_tip_W = s.F_tip_W;
  d.M_tip_W = s.M_tip_W;
  d.g_W = s.g_W;
  d.cur = s.cur;
  d.prev = s.prev;
  d.cur_t = s.cur_t;
  d.z = s.z;
  d.z_diff = s.z_diff;
  d.grid_converged = s.grid_converged;
  for (int j = 0; j < 3; ++j) d.node_hist[j] = s.node_hist[j];
  d.history_steps = s.history_steps;
  d.predictor_order = s.predictor_order;
  if (s.M != d.M) {
    // set_time_step() changed the intervals after the step: back to the step's layout.
    d.M = s.M;
    d.S = d.N / d.M;
    d.dense = d.unknowns() <= kDenseUnknowns;
    d.pattern_analyzed = false;
    d.lu_valid = false;
  } else if (s.lu_saved) {
    // The factorization the step replaced, computed again from its matrix (the same numbers).
    if (s.lu_valid) {
      const double c0_active = d.c0_active;
      d.c0_active = s.lu_c0;
      if (d.dense) {
        d.J_dense_ = s.J_dense;
      } else {
        d.J_ = s.J;
      }
      d.factorize_jacobian();
      d.c0_active = c0_active;
    }
    d.lu_valid = s.lu_valid;
    d.lu_c0 = s.lu_c0;
  }
  // The data of the last evaluation, as after the restored solve.
  d.grid = d.grid_converged;
  d.trial = d.cur;
}

double RodDynamics::time_s() const { return impl_->t; }
double RodDynamics::time_step_s() const { return impl_->opt.dt_s; }
int RodDynamics::intervals() const { return impl_->M; }
int RodDynamics::steps() const { return impl_->N; }
const std::vector<double>& RodDynamics::grid_s_m() const { return impl_->s_grid; }
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
std::vector<Eigen::Vector3d> RodDynamics::probe_positions_W_m() const {
  std::vector<Eigen::Vector3d> p;
  std::vector<Eigen::Matrix3d> R;
  for (const Eigen::VectorXd& y : impl_->grid_converged) {
    p.push_back(y.segment<3>(kP));
    R.push_back(Eigen::Map<const Mat3>(y.data() + kR));
  }
  return rod::probe_positions_at_samples(impl_->model, impl_->s_grid, p, R);
}

}  // namespace tcasim::cosserat
