// Generalized-alpha time integration of the beam FE on the Lie group (beam_fe/dynamics.hpp).
#include "beam_fe/dynamics.hpp"

#include <fmt/format.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "beam_fe/internal/dynamics_damping.hpp"
#include "beam_fe/internal/klu_refactoring.hpp"
#include "beam_fe/internal/quadrature.hpp"
#include "common/error.hpp"
#include "common/so3.hpp"
#include "rod/electric_thermal.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;
using internal::gauss_rule;

/// Index of entry (i, j) of a compressed column-major matrix in its values (it must exist).
int slot_of(const SpMat& A, int i, int j) {
  const int* inner = A.innerIndexPtr();
  const int* begin = inner + A.outerIndexPtr()[j];
  const int* end = inner + A.outerIndexPtr()[j + 1];
  const int* it = std::lower_bound(begin, end, i);
  if (it == end || *it != i) throw std::logic_error("beam_fe dynamics: entry outside the pattern");
  return static_cast<int>(it - inner);
}

}  // namespace

const char* to_string(BeamDynamicsSummary::Status s) {
  switch (s) {
    case BeamDynamicsSummary::Status::kConverged:
      return "converged";
    case BeamDynamicsSummary::Status::kMaxIterations:
      return "max-iterations";
    case BeamDynamicsSummary::Status::kSingular:
      return "singular-matrix";
    case BeamDynamicsSummary::Status::kNonFinite:
      return "non-finite";
    case BeamDynamicsSummary::Status::kNotRun:
      return "not-run";
  }
  return "unknown";
}

AlphaParameters alpha_parameters(double rho) {
  AlphaParameters p;
  p.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  p.alpha_f = rho / (rho + 1.0);
  p.gamma = 0.5 + p.alpha_f - p.alpha_m;
  p.beta = 0.25 * (p.gamma + 0.5) * (p.gamma + 0.5);
  return p;
}

struct BeamDynamics::Impl {
  Impl(const rod::RodModel& m, const DynamicsOptions& o);

  /// Loads at which the residual is evaluated: `current` (applied, electric drives' segments at
  /// the thermal states; gravity by this solver's nodal masses).
  void set_loads(const rod::Loads& loads);
  /// The tension drives' tensions into `s` (the TCA tensions are unknowns).
  void set_drive_tensions(State& s) const;
  /// Trial state and rates at increment x; the residual (unscaled) and, with J, dr/dx.
  VectorXd evaluate(const VectorXd& x, SpMat* J);
  /// Static residual (external loads subtracted) at `st`, tangent in material increments.
  VectorXd static_residual(const State& st, SpMat* K) const;
  bool within_tolerance(const VectorXd& r, double* scaled) const;
  BeamDynamicsSummary newton_static();
  /// The drives' segment temperatures of the converged state into temperatures_conv.
  void keep_temperatures();

  const rod::RodModel& model;
  DynamicsOptions opt;
  AlphaParameters ap;
  double tip_mass_kg = 0.0;  // DynamicsOptions::tip_mass_kg, else the model's
  // The loads of the current evaluation; the residual is taken at load factor 1.
  LoadCase current;
  Options fe;
  std::unique_ptr<Discretization> disc_static;
  int nodes = 0, free_dofs = 0, n_act = 0;
  int n_x = 0;                    // unknowns: free_dofs, then one tension per TCA
  std::vector<int> tca_actuator;  // actuator of each TCA unknown
  rod::ElectricThermalStates thermal;
  std::vector<std::vector<double>> temperatures_conv;  // per actuator, of the last converged step
  double h = 0.0, t = 0.0, L = 0.0, F_c = 1.0;
  // Coefficients of the affine maps x -> vdot, v (d vdot/dx, d v/dx) and strain rate c_e.
  double c_a = 0.0, c_v = 0.0, c_e = 0.0;
  // Mass: per element (order + 1)^2 entries int rho A N_a N_b ds; per node the row sum
  // int rho A N_a ds and the nodal rotational inertia diag.
  std::vector<double> elem_mass;
  std::vector<double> node_mass;
  std::vector<Vector3d> node_J;
  std::unique_ptr<damping::StrainRateHistory> kv;  // Kelvin-Voigt history (viscosity > 0)
  // Converged step n and trial step n + 1.
  State st, trial;
  VectorXd v, vd, a, v1, vd1, a1, x_last;
  SpMat K;
  internal::KluRefactoring lu;
  bool factored = false;           // lu holds a factorization of an earlier step Jacobian
  std::vector<int> inertia_slots;  // value index of every inertia entry, in assembly order
  Discretization::Floor floor{0.0, 0.0};
  double local_error = 0.0;  // local_error_m() of the last converged step
  // The state before the last step() call (undo_step); valid until undone.
  struct Saved {
    bool valid = false;
    State st;
    VectorXd v, vd, a, x_last;
    double t = 0.0, local_error = 0.0;
    rod::ElectricThermalStates thermal;
    std::vector<std::vector<double>> temperatures_conv;
    damping::StrainRateHistory::Snapshot kv;
  } saved;
  /// The step size h and what depends on it (c_a, c_e, the damping's c_e B and round-off floor).
  void set_step_size(double h_new);
  /// [Zienkiewicz1991]-type estimate of the step's local error (docs/conventions.md).
  double estimate_local_error() const;
};

BeamDynamics::Impl::Impl(const rod::RodModel& m, const DynamicsOptions& o) : model(m), opt(o) {
  require(std::isfinite(o.dt_s) && o.dt_s > 0.0, "dynamics.dt_s", o.dt_s, "must be > 0");
  require(o.rho_inf >= 0.0 && o.rho_inf <= 1.0, "dynamics.rho_inf", o.rho_inf, "must be in [0, 1]");
  require(std::isfinite(o.tolerance) && o.tolerance > 0.0, "dynamics.tolerance", o.tolerance,
          "must be > 0");
  require(o.max_iterations >= 1, "dynamics.max_iterations", o.max_iterations, "must be >= 1");
  if (o.tip_mass_kg) {
    require(std::isfinite(*o.tip_mass_kg) && *o.tip_mass_kg >= 0.0, "dynamics.tip_mass_kg",
            *o.tip_mass_kg, "must be >= 0");
  }
  tip_mass_kg = o.tip_mass_kg.value_or(m.tip_mass_kg);
  if (m.tip_constraint) {
    throw DomainError("FE dynamics: a tip_constraint is not supported in dynamics yet");
  }
  if (!m.obstacles.empty()) {
    throw DomainError("FE dynamics: obstacles are not supported in dynamics yet");
  }
  if (o.viscosity_Pa_s) {
    require(std::isfinite(*o.viscosity_Pa_s) && *o.viscosity_Pa_s >= 0.0, "dynamics.viscosity_Pa_s",
            *o.viscosity_Pa_s, "must be >= 0");
  }
  ap = alpha_parameters(o.rho_inf);
  h = o.dt_s;
  L = m.length_m;
  c_a = (1.0 - ap.alpha_m) / ((1.0 - ap.alpha_f) * ap.beta * h);
  c_v = ap.gamma / ap.beta;
  c_e = ap.gamma / (ap.beta * h);
  fe.elements = o.elements;
  fe.order = o.order;
  fe.integration = o.integration;
  // A viscosity profile's breakpoints are mesh nodes, as the body's own.
  const rod::Profile& eta_profile = m.material.viscosity_profile;
  const bool eta_varies = !o.viscosity_Pa_s && !eta_profile.is_constant();
  if (eta_varies) {
    for (const double s : eta_profile.breakpoints())
      if (s > 0.0 && s < m.length_m) fe.extra_knots_m.push_back(s);
  }
  disc_static = std::make_unique<Discretization>(m, fe);  // validates elements, order
  nodes = disc_static->node_count();
  free_dofs = 6 * (nodes - 1);
  n_act = static_cast<int>(m.actuators.size());
  for (int i = 0; i < n_act; ++i) {
    if (m.actuators[i].drive.type == rod::Drive::Type::kTca) tca_actuator.push_back(i);
  }
  n_x = free_dofs + static_cast<int>(tca_actuator.size());
  floor = disc_static->round_off_floor();

  // Consistent mass (3-point Gauss: exact for uniform quadratic elements) and nodal inertia.
  const int order = disc_static->order(), n = order + 1;
  std::vector<double> xi, w;
  gauss_rule(3, xi, w);
  elem_mass.assign(static_cast<std::size_t>(disc_static->element_count()) * n * n, 0.0);
  node_mass.assign(nodes, 0.0);
  node_J.assign(nodes, Vector3d::Zero());
  double N[3], dN[3];
  for (int e = 0; e < disc_static->element_count(); ++e) {
    const double s0 = disc_static->element_start_m(e), he = disc_static->element_length_m(e);
    for (std::size_t g = 0; g < xi.size(); ++g) {
      internal::shape(order, xi[g], N, dN);
      const double s = s0 + 0.5 * (xi[g] + 1.0) * he;
      const double wj = w[g] * 0.5 * he;
      const double rhoA = m.mass_per_length_kg_m(s);
      const rod::SectionProperties sp = m.section.properties_at(s);
      const double rho = m.material.density_profile.value(s, rod::Side::kRight);
      // [Till2019] / cosserat dynamics: rho J = diag(rho I_x, rho I_y, rho (I_x + I_y)).
      const Vector3d rhoJ(rho * sp.I_x_m4, rho * sp.I_y_m4, rho * (sp.I_x_m4 + sp.I_y_m4));
      for (int i = 0; i < n; ++i) {
        const int node = e * order + i;
        node_mass[node] += wj * rhoA * N[i];
        // Nodal quadrature of the rotational kinetic energy: weights int N_a ds.
        node_J[node] += wj * N[i] * rhoJ;
        for (int j = 0; j < n; ++j)
          elem_mass[(static_cast<std::size_t>(e) * n + i) * n + j] += wj * rhoA * N[i] * N[j];
      }
    }
  }
  const double eta_max = o.viscosity_Pa_s ? *o.viscosity_Pa_s
                         : eta_varies     ? eta_profile.max_value()
                                          : eta_profile.value(0.0);
  if (eta_max > 0.0) {
    kv = std::make_unique<damping::StrainRateHistory>(*disc_static, m, o.viscosity_Pa_s, ap, h);
    // The viscous stresses c_e B eps(n+1) - c_e B eps(n) are formed from the strains as the
    // elastic ones, with c_e B in place of K (c_e B = 56 K on the soft manipulator at dt 1 ms):
    // their round-off adds to the floor (docs/conventions.md "Beam FE dynamics").
    const auto [cB_se, cB_bt] = kv->max_added_stiffness();
    floor = disc_static->round_off_floor(cB_se, cB_bt);
  }
  v = vd = a = VectorXd::Zero(free_dofs);
}

void BeamDynamics::Impl::set_step_size(double h_new) {
  const double ratio = h_new / h;
  // The acceleration variable lags: a_n = vdot(t_n + (alpha_m - alpha_f) h) + O(h^2)
  // ([Chung1993]), a shift proportional to the step size. Rescaling a_n - vdot_n with the step
  // keeps a_n consistent with the new step (no spurious a-mode excited by a size change).
  a = vd + ratio * (a - vd);
  h = h_new;
  c_a = (1.0 - ap.alpha_m) / ((1.0 - ap.alpha_f) * ap.beta * h);
  c_e = ap.gamma / (ap.beta * h);
  if (kv) {
    kv->set_time_step(h);
    const auto [cB_se, cB_bt] = kv->max_added_stiffness();
    floor = disc_static->round_off_floor(cB_se, cB_bt);
  }
  // The step Jacobian scales with 1/h (inertia) and h (stiffness): a factorization of a much
  // different step size makes chord iterations contract poorly, so it is not reused.
  constexpr double kMaxReuseRatio = 1.5;
  if (ratio > kMaxReuseRatio || ratio < 1.0 / kMaxReuseRatio) factored = false;
}

double BeamDynamics::Impl::estimate_local_error() const {
  // Local error of the Newmark position update q1 = q + h v + h^2 ((1/2 - beta) a + beta a1)
  // against the third-order Taylor expansion q + h v + h^2/2 vdot + h^3/6 vdot', with the
  // generalized-alpha acceleration variable a_n = vdot(t_n + (alpha_m - alpha_f) h) + O(h^2)
  // ([Chung1993]; alpha_m - alpha_f = 1/2 - gamma) and vdot' ~ (a1 - a) / h
  // ([Zienkiewicz1991] for Newmark):
  //   e = (beta + (alpha_m - alpha_f)/2 - 1/6) h^3 vdot' = (beta - gamma/2 + 1/12) h^2 (a1 - a),
  // > 0 for every rho_inf ((gamma - 1/2)^2 / 4 + 1/12). The same on the rotation rows (body
  // frame, the Lie-algebra increment h x), times L.
  const double c = (ap.beta - 0.5 * ap.gamma + 1.0 / 12.0) * h * h;
  double e = 0.0;
  for (int k = 0; k + 1 < nodes; ++k) {
    const int b = 6 * k;
    e = std::max(e, c * (a1.segment<3>(b) - a.segment<3>(b)).norm());
    e = std::max(e, c * L * (a1.segment<3>(b + 3) - a.segment<3>(b + 3)).norm());
  }
  return e;
}

void BeamDynamics::Impl::set_loads(const rod::Loads& loads) {
  // Validated and applied; gravity by the consistent mass's row sums (node_mass, the 3-point
  // rule of the mass matrix). An electric drive's segments then take the thermal states (the
  // nodal forces do not depend on them).
  current = make_load_case(model, loads, node_mass, tip_mass_kg);
  std::vector<std::vector<tca::Segment>> segments(n_act);
  for (int i = 0; i < n_act; ++i) segments[i] = std::move(current.loads.actuators[i].segments);
  thermal.apply(segments);
  for (int i = 0; i < n_act; ++i) current.loads.actuators[i].segments = std::move(segments[i]);
}

void BeamDynamics::Impl::set_drive_tensions(State& s) const {
  disc_static->apply_prescribed_tensions(current, s, 1.0);
}

VectorXd BeamDynamics::Impl::static_residual(const State& s, SpMat* Kt) const {
  return disc_static->residual(s, current, 1.0, Kt);
}

bool BeamDynamics::Impl::within_tolerance(const VectorXd& r, double* scaled) const {
  bool ok = r.allFinite();
  double worst = 0.0;
  for (int i = 0; i < free_dofs; ++i) {
    const bool moment = i % 6 >= 3;
    const double unit = moment ? F_c * L : F_c;
    worst = std::max(worst, std::abs(r[i]) / unit);
    ok = ok && std::abs(r[i]) <= opt.tolerance * unit + (moment ? floor.moment : floor.force);
  }
  for (int i = free_dofs; i < n_x; ++i) {  // TCA rows [N]
    worst = std::max(worst, std::abs(r[i]) / F_c);
    ok = ok && std::abs(r[i]) <= opt.tolerance * F_c + floor.force;
  }
  if (scaled) *scaled = r.allFinite() ? worst : std::numeric_limits<double>::infinity();
  return ok;
}

VectorXd BeamDynamics::Impl::evaluate(const VectorXd& x, SpMat* Jout) {
  // Newmark and alpha relations ([Bruls2012] Eqs. (13)-(16)):
  //   q1 = q exp(h x), x = v + h (1/2 - beta) a + h beta a1,
  //   v1 = v + h (1 - gamma) a + h gamma a1,
  //   (1 - alpha_m) a1 + alpha_m a = (1 - alpha_f) vd1 + alpha_f vd.
  a1 = (x.head(free_dofs) - v - h * (0.5 - ap.beta) * a) / (ap.beta * h);
  v1 = v + h * (1.0 - ap.gamma) * a + h * ap.gamma * a1;
  vd1 = ((1.0 - ap.alpha_m) * a1 + ap.alpha_m * a - ap.alpha_f * vd) / (1.0 - ap.alpha_f);
  trial = st;
  for (int k = 1; k < nodes; ++k) {
    trial.p_W_m[k] += h * x.segment<3>(6 * (k - 1));
    trial.q_WB[k] =
        (st.q_WB[k] * so3::exp_quaternion(h * x.segment<3>(6 * (k - 1) + 3))).normalized();
  }
  set_drive_tensions(trial);
  for (std::size_t j = 0; j < tca_actuator.size(); ++j) {
    trial.tensions_N[tca_actuator[j]] = x[free_dofs + static_cast<int>(j)];
  }
  VectorXd r = disc_static->residual(trial, current, 1.0, Jout ? &K : nullptr);
  if (kv) kv->add_forces(trial, r, Jout ? &K : nullptr);
  // Inertia: consistent translational mass (world frame), nodal rotational inertia with the
  // gyroscopic term W x J W (body frame), the tip mass at the tip node.
  const int order = disc_static->order(), n = order + 1;
  for (int e = 0; e < disc_static->element_count(); ++e) {
    for (int i = 0; i < n; ++i) {
      const int ni = e * order + i;
      if (ni == 0) continue;
      for (int j = 0; j < n; ++j) {
        const int nj = e * order + j;
        if (nj == 0) continue;
        r.segment<3>(6 * (ni - 1)) +=
            elem_mass[(static_cast<std::size_t>(e) * n + i) * n + j] * vd1.segment<3>(6 * (nj - 1));
      }
    }
  }
  r.segment<3>(free_dofs - 6) += tip_mass_kg * vd1.segment<3>(free_dofs - 6);
  for (int k = 1; k < nodes; ++k) {
    const Vector3d W = v1.segment<3>(6 * (k - 1) + 3);
    const Vector3d JW = node_J[k].cwiseProduct(W);
    r.segment<3>(6 * (k - 1) + 3) +=
        node_J[k].cwiseProduct(vd1.segment<3>(6 * (k - 1) + 3)) + W.cross(JW);
  }
  if (!Jout) return r;
  // dr/dx = K T h + c_a M + c_v C_gyro, T = diag(I, Jr(h x_theta)) per node (the TCA columns
  // are the tensions themselves: T = I there), in place in K's pattern: T mixes only the three
  // rotation columns of a node, which share their rows, and the inertia blocks lie inside the
  // element blocks.
  double* val = K.valuePtr();
  const int* outer = K.outerIndexPtr();
  for (int k = 1; k < nodes; ++k) {
    const int b = 6 * (k - 1);
    for (int i = outer[b]; i < outer[b + 3]; ++i) val[i] *= h;
    const Matrix3d hJr = h * so3::right_jacobian(h * x.segment<3>(b + 3));
    const int count = outer[b + 4] - outer[b + 3];
    if (outer[b + 5] - outer[b + 4] != count || outer[b + 6] - outer[b + 5] != count)
      throw std::logic_error("beam_fe dynamics: rotation columns of a node differ in pattern");
    double* c0 = val + outer[b + 3];
    double* c1 = val + outer[b + 4];
    double* c2 = val + outer[b + 5];
    for (int i = 0; i < count; ++i) {
      const double k0 = c0[i], k1 = c1[i], k2 = c2[i];
      c0[i] = k0 * hJr(0, 0) + k1 * hJr(1, 0) + k2 * hJr(2, 0);
      c1[i] = k0 * hJr(0, 1) + k1 * hJr(1, 1) + k2 * hJr(2, 1);
      c2[i] = k0 * hJr(0, 2) + k1 * hJr(1, 2) + k2 * hJr(2, 2);
    }
  }
  std::size_t next = 0;
  auto add = [&](int i, int j, double value) {
    if (next == inertia_slots.size()) inertia_slots.push_back(slot_of(K, i, j));
    val[inertia_slots[next++]] += value;
  };
  for (int e = 0; e < disc_static->element_count(); ++e) {
    for (int i = 0; i < n; ++i) {
      const int ni = e * order + i;
      if (ni == 0) continue;
      for (int j = 0; j < n; ++j) {
        const int nj = e * order + j;
        if (nj == 0) continue;
        const double mij = c_a * elem_mass[(static_cast<std::size_t>(e) * n + i) * n + j];
        for (int c = 0; c < 3; ++c) add(6 * (ni - 1) + c, 6 * (nj - 1) + c, mij);
      }
    }
  }
  for (int c = 0; c < 3; ++c) add(free_dofs - 6 + c, free_dofs - 6 + c, c_a * tip_mass_kg);
  for (int k = 1; k < nodes; ++k) {
    const int b = 6 * (k - 1) + 3;
    const Vector3d W = v1.segment<3>(b);
    const Matrix3d Jm = node_J[k].asDiagonal();
    // d(W x J W)/dW = hat(W) J - hat(J W).
    const Matrix3d G = c_a * Jm + c_v * (so3::hat(W) * Jm - so3::hat(Jm * W));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) add(b + i, b + j, G(i, j));
  }
  if (Jout != &K) *Jout = K;
  return r;
}

void BeamDynamics::Impl::keep_temperatures() {
  temperatures_conv.assign(n_act, {});
  for (const int i : tca_actuator) {
    for (const tca::Segment& sg : current.loads.actuators[i].segments) {
      temperatures_conv[i].push_back(sg.temperature_K);
    }
  }
}

BeamDynamicsSummary BeamDynamics::Impl::newton_static() {
  BeamDynamicsSummary sum;
  SpMat Ks;
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> slu;
  for (int it = 0;; ++it) {
    set_drive_tensions(st);
    const VectorXd r = static_residual(st, &Ks);
    if (within_tolerance(r, &sum.residual)) {
      sum.status = BeamDynamicsSummary::Status::kConverged;
      return sum;
    }
    if (!r.allFinite()) {
      sum.status = BeamDynamicsSummary::Status::kNonFinite;
      sum.message = "the static residual is not finite";
      return sum;
    }
    if (it == opt.max_iterations) {
      sum.status = BeamDynamicsSummary::Status::kMaxIterations;
      sum.message =
          fmt::format("static state: no convergence in {} Newton iterations", opt.max_iterations);
      return sum;
    }
    Ks.makeCompressed();
    slu.compute(Ks);
    if (slu.info() != Eigen::Success) {
      sum.status = BeamDynamicsSummary::Status::kSingular;
      sum.message = "the static tangent could not be factorized";
      return sum;
    }
    const VectorXd dx = slu.solve(-r);
    disc_static->retract(st, dx);
    ++sum.iterations;
  }
}

BeamDynamics::BeamDynamics(const rod::RodModel& model, const DynamicsOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}
BeamDynamics::~BeamDynamics() = default;

BeamDynamicsSummary BeamDynamics::initialize(const rod::Loads& loads) {
  Impl& d = *impl_;
  d.thermal.reset(d.model, loads);
  d.set_loads(loads);
  d.F_c = rod::characteristic_force_N(d.model, loads, d.tip_mass_kg);
  d.t = 0.0;
  d.st = d.disc_static->reference_state();
  // The static solve is the starting point of this solver's own static Newton iteration.
  const Summary s = solve(d.model, loads, d.fe, d.st);
  if (!s.converged()) d.st = d.disc_static->reference_state();
  d.st.load_factor = 1.0;
  BeamDynamicsSummary sum = d.newton_static();
  sum.iterations += s.iterations;
  if (!sum.converged()) return sum;
  d.v.setZero();
  d.vd.setZero();
  d.a.setZero();
  d.x_last = VectorXd::Zero(d.n_x);
  for (std::size_t j = 0; j < d.tca_actuator.size(); ++j) {
    d.x_last[d.free_dofs + static_cast<int>(j)] = d.st.tensions_N[d.tca_actuator[j]];
  }
  if (d.kv) d.kv->reset(d.st);
  d.keep_temperatures();
  d.local_error = 0.0;
  d.saved.valid = false;
  return sum;
}

BeamDynamicsSummary BeamDynamics::step(const rod::Loads& loads) {
  Impl& d = *impl_;
  BeamDynamicsSummary sum;
  d.saved.valid = true;
  d.saved.st = d.st;
  d.saved.v = d.v;
  d.saved.vd = d.vd;
  d.saved.a = d.a;
  d.saved.x_last = d.x_last;
  d.saved.t = d.t;
  d.saved.local_error = d.local_error;
  d.saved.thermal = d.thermal;
  d.saved.temperatures_conv = d.temperatures_conv;
  if (d.kv) d.saved.kv = d.kv->snapshot();
  // Electric drives: the temperatures over [t, t + dt] first (they do not depend on the
  // mechanics), then the mechanics at the new temperatures.
  const rod::ElectricThermalStates thermal_n = d.thermal;
  if (!d.thermal.advance(d.model, d.t, d.h, sum.message)) {
    sum.status = BeamDynamicsSummary::Status::kNonFinite;
    return sum;
  }
  d.set_loads(loads);
  // Restores the thermal states of t_n when the mechanical step fails.
  const auto failed = [&](BeamDynamicsSummary::Status status, std::string message) {
    d.thermal = thermal_n;
    sum.status = status;
    sum.message = std::move(message);
    return sum;
  };
  // Predictor: a_{n+1} = a_n, the TCA tensions of t_n.
  VectorXd x = d.x_last;
  x.head(d.free_dofs) = d.v + d.h * 0.5 * d.a;
  // Chord (simplified Newton) iterations with the last factorization, kept across steps; a
  // fresh Jacobian when one contracts the residual by less than kChordContraction, after
  // kMaxChordSteps chord steps, or always without reuse_factorization.
  constexpr double kChordContraction = 0.25;
  constexpr int kMaxChordSteps = 6;
  bool fresh = !d.factored || !d.opt.reuse_factorization;
  int chord_steps = 0;
  double r_prev = std::numeric_limits<double>::infinity();
  VectorXd x_prev = x;
  while (true) {
    const VectorXd r = d.evaluate(x, fresh ? &d.K : nullptr);
    if (d.within_tolerance(r, &sum.residual)) break;
    if (!r.allFinite()) {
      return failed(BeamDynamicsSummary::Status::kNonFinite, "the residual is not finite");
    }
    if (!fresh && (sum.residual > kChordContraction * r_prev || chord_steps >= kMaxChordSteps)) {
      // A chord step that grew the residual is undone: the fresh Jacobian is taken at the
      // iterate before it (from the grown one a full Newton step can diverge: the released
      // cantilever at dt 2 ms, t = 0.114 s; docs/conventions.md "Beam FE dynamics").
      fresh = true;
      if (chord_steps > 0 && sum.residual > r_prev) x = x_prev;
      continue;
    }
    if (sum.iterations == d.opt.max_iterations) {
      return failed(BeamDynamicsSummary::Status::kMaxIterations,
                    fmt::format("no convergence in {} Newton iterations (scaled residual {:.3e})",
                                d.opt.max_iterations, sum.residual));
    }
    if (fresh) {
      d.factored = d.lu.factorize(d.K);
      if (!d.factored) {
        return failed(BeamDynamicsSummary::Status::kSingular,
                      "the iteration matrix could not be factorized");
      }
      chord_steps = 0;
    } else {
      ++chord_steps;
    }
    x_prev = x;
    VectorXd dx = -r;
    if (!d.lu.solve(dx) || !dx.allFinite()) {
      return failed(BeamDynamicsSummary::Status::kNonFinite, "the Newton step is not finite");
    }
    x += dx;
    ++sum.iterations;
    r_prev = sum.residual;
    fresh = !d.opt.reuse_factorization;
  }
  sum.status = BeamDynamicsSummary::Status::kConverged;
  d.local_error = d.estimate_local_error();
  if (d.kv) d.kv->advance(d.trial);
  d.st = d.trial;
  d.v = d.v1;
  d.vd = d.vd1;
  d.a = d.a1;
  d.x_last = x;
  d.t += d.h;
  d.keep_temperatures();
  return sum;
}

VectorXd BeamDynamics::step_residual(const rod::Loads& loads, const VectorXd& x, SpMat* Jac) {
  Impl& d = *impl_;
  d.set_loads(loads);
  VectorXd r = d.evaluate(x, Jac);
  for (int i = 0; i < d.n_x; ++i) {
    const double unit = i < d.free_dofs && i % 6 >= 3 ? d.F_c * d.L : d.F_c;
    r[i] /= unit;
    if (Jac) Jac->row(i) /= unit;
  }
  return r;
}

void BeamDynamics::set_time_step(double dt_s) {
  require(std::isfinite(dt_s) && dt_s > 0.0, "dynamics.dt_s", dt_s, "must be > 0");
  if (dt_s != impl_->h) impl_->set_step_size(dt_s);
}

double BeamDynamics::local_error_m() const { return impl_->local_error; }

int BeamDynamics::error_order() const { return 2; }

void BeamDynamics::undo_step() {
  Impl& d = *impl_;
  if (!d.saved.valid) return;
  d.st = d.saved.st;
  d.v = d.saved.v;
  d.vd = d.saved.vd;
  d.a = d.saved.a;
  d.x_last = d.saved.x_last;
  d.t = d.saved.t;
  d.local_error = d.saved.local_error;
  d.thermal = d.saved.thermal;
  d.temperatures_conv = d.saved.temperatures_conv;
  if (d.kv) d.kv->restore(d.saved.kv);
  d.saved.valid = false;
}

double BeamDynamics::time_s() const { return impl_->t; }
double BeamDynamics::time_step_s() const { return impl_->h; }
const State& BeamDynamics::state() const { return impl_->st; }
const Discretization& BeamDynamics::discretization() const { return *impl_->disc_static; }
const VectorXd& BeamDynamics::velocities() const { return impl_->v; }
Vector3d BeamDynamics::tip_position_W_m() const { return impl_->st.p_W_m.back(); }
Matrix3d BeamDynamics::tip_rotation_W() const { return impl_->st.q_WB.back().toRotationMatrix(); }

double BeamDynamics::kinetic_energy_J() const {
  const Impl& d = *impl_;
  const int order = d.disc_static->order(), n = order + 1;
  double T = 0.0;
  for (int e = 0; e < d.disc_static->element_count(); ++e) {
    for (int i = 0; i < n; ++i) {
      const int ni = e * order + i;
      if (ni == 0) continue;
      for (int j = 0; j < n; ++j) {
        const int nj = e * order + j;
        if (nj == 0) continue;
        T += 0.5 * d.elem_mass[(static_cast<std::size_t>(e) * n + i) * n + j] *
             d.v.segment<3>(6 * (ni - 1)).dot(d.v.segment<3>(6 * (nj - 1)));
      }
    }
  }
  for (int k = 1; k < d.nodes; ++k) {
    const Vector3d W = d.v.segment<3>(6 * (k - 1) + 3);
    T += 0.5 * W.dot(d.node_J[k].cwiseProduct(W));
  }
  return T + 0.5 * d.tip_mass_kg * d.v.segment<3>(d.free_dofs - 6).squaredNorm();
}

double BeamDynamics::potential_energy_J() const {
  const Impl& d = *impl_;
  const rod::RodModel& m = d.model;
  // Strain energy with the element's own quadrature (its gradient is the element residual).
  std::vector<double> xi, w;
  const int points = d.fe.order + (d.fe.integration == Integration::kFull ? 1 : 0);
  gauss_rule(points, xi, w);
  const std::vector<PointStrain> eps = d.disc_static->strains(d.st);
  double U = 0.0;
  for (std::size_t k = 0; k < eps.size(); ++k) {
    const int e = static_cast<int>(k / xi.size());
    const double wj = w[k % xi.size()] * 0.5 * d.disc_static->element_length_m(e);
    const double s = eps[k].s_m;
    const Vector3d de = eps[k].nu_B - Vector3d::UnitZ();
    const Vector3d dom = eps[k].omega_B - m.reference_curvature_at(s);
    U += wj * 0.5 *
         (de.dot(m.shear_extension_stiffness(s).cwiseProduct(de)) +
          dom.dot(m.bending_torsion_stiffness(s).cwiseProduct(dom)));
  }
  const Vector3d& g_W = d.current.loads.gravity_W_m_s2;
  for (int k = 0; k < d.nodes; ++k) U -= d.node_mass[k] * g_W.dot(d.st.p_W_m[k]);
  U -= (d.current.loads.tip_force_W_N + d.tip_mass_kg * g_W).dot(d.st.p_W_m.back());
  const std::vector<double> l = d.disc_static->string_lengths(d.st);
  for (int i = 0; i < d.n_act; ++i) {
    U += m.actuators[i].count * d.st.tensions_N[i] * (l[i] - m.actuators[i].rest_length_m);
  }
  return U;
}

std::vector<double> BeamDynamics::tensions_N() const { return impl_->st.tensions_N; }

std::vector<std::vector<double>> BeamDynamics::segment_temperatures_K() const {
  return impl_->temperatures_conv;
}

std::vector<double> BeamDynamics::elongations_m() const {
  const Impl& d = *impl_;
  std::vector<double> l = d.disc_static->string_lengths(d.st);
  for (int i = 0; i < d.n_act; ++i) l[i] -= d.model.actuators[i].rest_length_m;
  return l;
}

}  // namespace tcasim::beam_fe
