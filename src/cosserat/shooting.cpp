// The shooting solver's driver: construction, the solve sequence (warm or cold start,
// direct solve, continuation) and results. The stages live in the files named in
// cosserat/internal/shooting_impl.hpp.
#include "cosserat/shooting.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "cosserat/internal/layout.hpp"
#include "cosserat/internal/shooting_impl.hpp"
#include "rod/probes.hpp"

namespace tcasim::cosserat {

using namespace stage_names;

const char* to_string(Summary::Status s) {
  switch (s) {
    case Summary::Status::kConverged:
      return "converged";
    case Summary::Status::kMaxIterations:
      return "max_iterations";
    case Summary::Status::kLineSearchFailed:
      return "line_search_failed";
    case Summary::Status::kSingularJacobian:
      return "singular_jacobian";
    case Summary::Status::kContinuationFailed:
      return "continuation_failed";
    case Summary::Status::kInitialPointFailed:
      return "initial_point_failed";
    case Summary::Status::kContactNotSettled:
      return "contact_not_settled";
    case Summary::Status::kNotRun:
      return "not_run";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------------------
ShootingSolver::Impl::Impl(const rod::RodModel& m, const Options& o,
                           std::unique_ptr<internal::Layout> layout_)
    : TipConditions(m, std::move(layout_), o.jacobian == JacobianMethod::kSensitivity),
      free_options(o),
      options(with_jacobian_fallback(validated(m, o), nx)),
      fine_level(dim, nx, options.integrator, options.kinematics,
                 options.jacobian == JacobianMethod::kSensitivity, piece_hooks()) {
  const bool sensitivities = options.jacobian == JacobianMethod::kSensitivity;
  ode::IntegratorOptions coarse = options.integrator;
  coarse.steps = options.coarse_steps;
  const bool use_coarse = ode::is_fixed_step(options.integrator.method) &&
                          options.coarse_steps > 0 &&
                          2 * options.coarse_steps <= options.integrator.steps;
  if (use_coarse)
    coarse_level.emplace(dim, nx, coarse, options.kinematics, sensitivities, piece_hooks());
  ode::IntegratorOptions mid = coarse;
  mid.steps = 2 * options.coarse_steps;
  const bool use_mid = use_coarse && 2 * mid.steps <= options.integrator.steps;
  if (use_mid) mid_level.emplace(dim, nx, mid, options.kinematics, sensitivities, piece_hooks());
  y.resize(dim);
  if (sensitivities) Y.resize(dim * (1 + nx));
  level = &fine_level;
  // make_result samples at every step node of the fine level's grid (output_level): the
  // fine IVPs can record those samples for it (see Samples).
  if (!m.obstacles.empty()) build_contact_grid();
  record_samples = ode::is_fixed_step(options.integrator.method) &&
                   options.kinematics == Kinematics::kFlat && options.centerline_intervals == 0;
  sample_recorder = [this](double s, const Eigen::VectorXd& yy) {
    samples.s.push_back(s);
    samples.y.insert(samples.y.end(), yy.data(), yy.data() + yy.size());
  };
}

Options ShootingSolver::Impl::validated(const rod::RodModel& m, Options o) {
  require(m.length_m > 0.0 && std::isfinite(m.length_m), "model.length_m", m.length_m,
          "must be > 0");
  require(o.tolerance > 0.0, "options.tolerance", o.tolerance, "must be > 0");
  require(o.coarse_steps >= 0 && o.coarse_steps % 2 == 0, "options.coarse_steps", o.coarse_steps,
          "must be even and >= 0");
  require(o.max_iterations >= 1, "options.max_iterations", o.max_iterations, "must be >= 1");
  require(o.max_line_search_steps >= 1, "options.max_line_search_steps", o.max_line_search_steps,
          "must be >= 1");
  require(o.min_continuation_step > 0.0 && o.min_continuation_step < 1.0,
          "options.min_continuation_step", o.min_continuation_step, "must be in (0, 1)");
  require(o.centerline_intervals >= 0 && o.centerline_intervals % 2 == 0,
          "options.centerline_intervals", o.centerline_intervals,
          "must be even and >= 0 (a sample must lie at L/2)");
  if (ode::is_fixed_step(o.integrator.method)) {
    require(o.integrator.steps % 2 == 0, "options.integrator.steps", o.integrator.steps,
            "must be even (a node must lie at L/2)");
    require(o.centerline_intervals == 0 || o.integrator.steps % o.centerline_intervals == 0,
            "options.centerline_intervals", o.centerline_intervals,
            "must divide options.integrator.steps = " + std::to_string(o.integrator.steps));
  }
  require(o.kinematics == Kinematics::kFlat || o.integrator.method == ode::Method::kRk4,
          "options.integrator.method", "cvode",
          "must be rk4 with options.kinematics = lie_group (a fixed-step method)");
  o.integrator.output_intervals = 0;
  if (!m.obstacles.empty()) {
    // Contact points are the step nodes of one fixed-step grid (docs/conventions.md
    // "Contact in the shooting method"); the coarse levels do not carry the multipliers.
    require(ode::is_fixed_step(o.integrator.method), "options.integrator.method", "cvode",
            "must be a fixed-step method (rk4, rk6, rk8) with obstacles: the contact points are "
            "its step nodes");
    require(o.kinematics == Kinematics::kFlat, "options.kinematics", "lie_group",
            "must be flat with obstacles");
    require(o.centerline_intervals == 0, "options.centerline_intervals", o.centerline_intervals,
            "must be 0 (every step node) with obstacles");
    o.coarse_steps = 0;
  }
  return o;
}

Options ShootingSolver::Impl::with_jacobian_fallback(Options o, int n_unknowns) {
  if (o.jacobian == JacobianMethod::kSensitivity &&
      n_unknowns > internal::kMaxSensitivityUnknowns) {
    o.jacobian = JacobianMethod::kForwardDifference;
  }
  return o;
}

Summary ShootingSolver::Impl::solve(const rod::Loads& act, Solution& sol) {
  if (!model.obstacles.empty()) return contact_solve(act, sol);  // 3-D layout only
  if (sol.valid && sol.unknowns.allFinite()) layout->reduce_unknowns(sol.unknowns);
  Summary summary = solve_in_layout(act, sol);
  summary.planar = layout->reduced();
  if (sol.unknowns.size() == nx) layout->embed_unknowns(sol.unknowns);
  if (sol.tip_state.size() == dim) {
    Eigen::VectorXd tip;
    layout->embed_state(sol.tip_state, tip);
    sol.tip_state = std::move(tip);
    equilibrium(act, sol.unknowns, sol.tip_state, summary);  // cT, f_ext_W as finish() set
  }
  return summary;
}

Summary ShootingSolver::Impl::solve_in_layout(const rod::Loads& act, Solution& sol) {
  const auto t0 = std::chrono::steady_clock::now();
  Summary summary;
  ivp_count = 0;
  acc_full_load = false;
  coarse_jacobian_x.resize(0);  // a solve never depends on where an earlier one took Jacobians
  // Messages are built only on failure (solve is called in sweeps and design loops).
  if (static_cast<int>(act.actuators.size()) != n_act) {
    throw_input_error("actuation.actuators", static_cast<double>(act.actuators.size()),
                      "must have one entry per model actuator (" + std::to_string(n_act) + ")");
  }
  for (int i = 0; i < n_act; ++i) {
    if (unknown_of[i] >= 0 && act.actuators[i].segments.empty()) {
      throw_input_error("actuation.actuators[" + std::to_string(i) + "].segments", 0.0,
                        "must not be empty for a TCA drive");
    }
  }
  const bool warm = sol.valid && sol.unknowns.size() == nx && sol.unknowns.allFinite();
  auto done = [&](Summary::Status st, std::string why, const Eigen::VectorXd& x) {
    summary.status = st;
    summary.message = st == Summary::Status::kConverged ? std::string() : std::move(why);
    finish(act, x, sol, summary);
    sol.valid = st == Summary::Status::kConverged;
    record_path(sol, warm, sol.valid, actuation_vector(act));
    summary.ivp_count = ivp_count;
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return summary;
  };

  std::string why;
  if (warm) {
    // A sweep: start from the extrapolation along the path, with a fresh (coarse-level)
    // sensitivity Jacobian there if there is a coarse level, else the last one; fall back
    // to the last solution if that start does not converge.
    Eigen::VectorXd xp;
    Eigen::MatrixXd Jp;
    if (!coarse_level || !coarse_level->has_sensitivities()) Jp = sol.jacobian;
    if (extrapolate_path(sol, actuation_vector(act), nx, xp) &&
        newton(act, 1.0, xp, Jp, summary, why, options.tolerance) == Summary::Status::kConverged) {
      sol.jacobian = Jp;
      sol.coarse_unknowns.resize(0);
      sol.coarse_jacobian.resize(0, 0);
      return done(Summary::Status::kConverged, "", xp);
    }
  }
  bool loaded_guess = false;
  Eigen::VectorXd x;
  Eigen::MatrixXd J = (warm && sol.jacobian.rows() == nx) ? sol.jacobian : Eigen::MatrixXd();
  // A warm point farther from convergence than the cold path's start runs the cold path
  // (with the warm Jacobian on the coarse level), and the warm start only if that fails.
  const bool start_warm = warm && warm_start_pays(act, sol, J, x, loaded_guess);
  if (!warm && omega_star_varies) {
    set_parameters(act, 1.0, Eigen::VectorXd::Zero(nx));
    if (!f_ext_W.isZero(0.0) &&
        omega_star_homotopy(act, sol, x, J, summary, why) == Summary::Status::kConverged) {
      sol.jacobian = J;
      return done(Summary::Status::kConverged, "", x);
    }
    J.resize(0, 0);  // the ordinary cold start, as without the homotopy
    coarse_jacobian_x.resize(0);
  }
  if (start_warm) {
    x = sol.unknowns;
  } else if (!warm) {
    x = initial_guess(act, 1.0, true, &loaded_guess);
  }
  Summary::Status st = direct_solve(act, sol, start_warm, x, J, summary, why);
  if (st != Summary::Status::kConverged && warm && !start_warm) {
    x = sol.unknowns;
    J = sol.jacobian;
    std::string warm_why;
    st = direct_solve(act, sol, true, x, J, summary, warm_why);
    why = "from the guess: " + why + "; from the warm start: " + warm_why;
  } else if (st != Summary::Status::kConverged && loaded_guess) {
    // Strong gravity can bend the guess toward another equilibrium or out of Newton's
    // reach: retry from the guess without it before continuation.
    x = initial_guess(act, 1.0, false);
    J.resize(0, 0);
    std::string retry_why;
    st = direct_solve(act, sol, false, x, J, summary, retry_why);
    why = "from the guess with gravity: " + why + "; without: " + retry_why;
  }
  if (st == Summary::Status::kConverged || !options.continuation) {
    sol.jacobian = J;
    return done(st, why, x);
  }

  // Continuation in the load fraction lambda, warm-starting each step (fine level only).
  sol.coarse_unknowns.resize(0);
  sol.coarse_jacobian.resize(0, 0);
  st = continuation(act, x, J, summary, why);
  sol.jacobian = J;
  return done(st, why, x);
}

double ShootingSolver::Impl::equilibrium_residual(const Eigen::VectorXd& r,
                                                  double characteristic_force_N) const {
  const double k_c = K_nu.maxCoeff();  // constraint rows hold c . (p - p_target) / L
  double force = 0.0;
  for (int i = 0; i < r.size(); ++i) {
    const bool constraint = n_con > 0 && i >= k_con && i < k_con + n_con;
    force = std::max(force, std::abs(r[i]) * (constraint ? k_c : Fc));
  }
  return force / characteristic_force_N;
}

void ShootingSolver::Impl::finish(const rod::Loads& act, const Eigen::VectorXd& x, Solution& sol,
                                  Summary& summary) {
  Eigen::VectorXd r;
  summary.characteristic_force_N = rod::characteristic_force_N(model, act);
  summary.equilibrium_residual.reset();
  sol.unknowns = x;
  sol.tensions_N.assign(n_act, 0.0);
  sol.elongations_m.assign(n_act, 0.0);
  if (acc_full_load && x_acc.size() == x.size() && x_acc == x) {
    set_parameters(act, 1.0, x);  // no IVP: y(L) of this point is known
    y = y_acc;
    samples.valid = false;  // they belong to y (Samples)
    if (!tip_residual(act, 1.0, x, y, r)) r.resize(0);
  } else if (!residual(act, 1.0, x, r)) {
    // Only the last accepted point of a failed continuation can land here; keep finite zeros.
    sol.tip_state.resize(0);
    return;
  }
  sol.tip_state = y;
  if (r.size() == nx)
    summary.equilibrium_residual = equilibrium_residual(r, summary.characteristic_force_N);
  for (int i = 0; i < n_act; ++i) {
    sol.tensions_N[i] = cT[i] / count[i];
    sol.elongations_m[i] = y[delta_offset + i];
  }
}

rod::Result ShootingSolver::Impl::make_result(const rod::Loads& act, const Solution& sol,
                                              const Summary& summary) {
  rod::Result res;
  res.scenario = model.name;
  res.method = "cosserat";
  if (ode::is_fixed_step(options.integrator.method)) {
    res.discretization = {{"steps", static_cast<double>(options.integrator.steps)}};
    // RK4 (the paper's scheme) is the default and has no key; other schemes name their order.
    if (options.integrator.method != ode::Method::kRk4) {
      res.discretization.push_back(
          {"order", static_cast<double>(ode::order_of(options.integrator.method))});
    }
  } else {
    res.discretization = {{"rtol", options.integrator.relative_tolerance}};
  }
  res.converged = summary.converged();
  res.iterations = summary.iterations;
  res.residual = std::isfinite(summary.residual) ? summary.residual : 0.0;
  res.wall_time_s = summary.wall_time_s;
  res.message = summary.message;
  res.actuators.resize(n_act);
  for (int i = 0; i < n_act; ++i) res.actuators[i].name = model.actuators[i].name;

  // The IVP runs in this Impl's layout (the planar one for a solution in the plane, see
  // ShootingSolver::make_result); what is reported is embedded in the 3-D state.
  Eigen::VectorXd x = sol.unknowns;
  layout->reduce_unknowns(x);
  if (x.size() != nx || !x.allFinite()) {
    res.converged = false;
    if (res.message.empty()) res.message = "no solution to report";
    return res;
  }
  if (!output_level) {
    // Samples at every step node, or at centerline_intervals equal intervals (validated to
    // divide the steps); CVODE at 64 intervals by default.
    ode::IntegratorOptions io = options.integrator;
    io.output_intervals = options.centerline_intervals;
    if (io.method == ode::Method::kCvode && io.output_intervals == 0) io.output_intervals = 64;
    output_level.emplace(dim, 0, io, options.kinematics, false, piece_hooks());
  }
  set_parameters(act, 1.0, x);
  // The samples' count without knots inside (a hint: the vectors grow if there are more).
  int intervals = options.centerline_intervals;
  if (intervals == 0) {
    intervals = ode::is_fixed_step(options.integrator.method) ? options.integrator.steps : 64;
  }
  res.centerline_s_m.reserve(intervals + 1);
  res.centerline_p_W_m.reserve(intervals + 1);
  res.centerline_R_WB.reserve(intervals + 1);
  // With probes, the layout's state at every sample: the start of each probe's integration.
  std::vector<Eigen::VectorXd> sample_states;
  Eigen::VectorXd y3;
  auto observer = [&](double s, const Eigen::VectorXd& yy) {
    layout->embed_state(yy, y3);
    res.centerline_s_m.push_back(s);
    res.centerline_p_W_m.push_back(y3.segment<3>(kP));
    res.centerline_R_WB.push_back(Eigen::Map<const Mat3>(y3.data() + kR));
    if (!model.probes.empty()) sample_states.push_back(yy);
  };
  // The accepted point's samples when the memo holds this IVP (the one output_level would
  // integrate: the same grid, right-hand side and parameters), else the IVP again.
  bool sampled = true;
  if (!model.obstacles.empty()) {
    // The IVP with the solution's contact forces (zero when the multipliers are missing).
    std::vector<double> lam = sol.contact_lambda_N;
    if (static_cast<int>(lam.size()) != contact_grid.pairs())
      lam.assign(static_cast<std::size_t>(contact_grid.pairs()), 0.0);
    const ode::Observer node_observer = observer;
    sampled = contact_ivp(act, x, lam, 0, contact_iv, &node_observer);
    if (sampled) res.contacts = contact_results(lam, contact_iv);
  } else if (acc_samples.valid && memo_answers(x, &fine_level)) {
    Eigen::VectorXd yy(dim);
    for (std::size_t k = 0; k < acc_samples.s.size(); ++k) {
      yy = Eigen::Map<const Eigen::VectorXd>(acc_samples.y.data() + k * dim, dim);
      observer(acc_samples.s[k], yy);
    }
    y = y_acc;
  } else {
    initial_state(x, y);
    sampled = output_level->integrate(rhs, L, y, observer);
  }
  samples.valid = false;  // y is no longer the last recorded IVP's (Samples)
  if (!sampled) {
    res.converged = false;
    res.message = "IVP failed while sampling the solution";
    res.centerline_s_m.clear();
    res.centerline_p_W_m.clear();
    res.centerline_R_WB.clear();
    return res;
  }
  layout->embed_state(y, y3);
  res.tip_position_W_m = y3.segment<3>(kP);
  res.tip_R_WB = Eigen::Map<const Mat3>(y3.data() + kR);
  if (!probe_results(res, sample_states)) {
    res.converged = false;
    res.message = "IVP failed while evaluating the probes";
    return res;
  }
  if (n_con > 0) res.tip_reaction_force_W_N = reaction_W(x);
  for (int i = 0; i < n_act; ++i) {
    res.actuators[i].tension_N = cT[i] / count[i];
    res.actuators[i].elongation_m = y3[kDelta + i];
    rod::set_coil_contacts(model.actuators[i], act.actuators[i].segments, res.actuators[i]);
  }
  try {
    res.bending_radius_m = rod::three_point_inner_radius(model, res.centerline_s_m,
                                                         res.centerline_p_W_m, res.centerline_R_WB);
  } catch (const DomainError&) {
    res.bending_radius_m.reset();
  }
  return res;
}

rod::Wrench ShootingSolver::Impl::base_reaction(const Eigen::VectorXd& x,
                                                const rod::Result& res) const {
  // The total section wrench at s = 0 (the rod's n(0), m(0) and the strings leaving the base)
  // balances everything applied to the rod beyond it (TipConditions::equilibrium): the clamp
  // applies its opposite.
  const Mat3& R0 = model.R_WB0;
  Vec3 n = R0 * K_nu.cwiseProduct(x.head<3>());  // x holds nu(0) - nu*
  Vec3 m = R0 * K_omega.cwiseProduct(x.segment<3>(3) - omega_star);
  for (int i = 0; i < n_act; ++i) {
    if (!from_base(i)) continue;
    const rod::Routing& ro = model.actuators[i].routing;
    const Vec3 r0 = ro.r(0.0);
    const Vec3 t0 =
        R0 * (nu_star + x.head<3>() + x.segment<3>(3).cross(r0) + ro.dr(0.0)).normalized();
    const Vec3 f = count[i] * res.actuators[i].tension_N * t0;
    n += f;
    m += (R0 * r0).cross(f);
  }
  rod::Wrench w;
  w.force_W_N = -n;
  w.moment_W_Nm = -m;
  return w;
}

bool ShootingSolver::Impl::probe_results(rod::Result& res,
                                         const std::vector<Eigen::VectorXd>& sample_states) {
  const std::vector<double>& s = res.centerline_s_m;
  Eigen::VectorXd yp(dim), y3;
  for (const rod::Probe& probe : model.probes) {
    const int at = rod::sample_at(s, probe.s_m);
    if (at >= 0) {
      res.probes.push_back({probe.name, rod::probe_position_W_m(probe, res.centerline_p_W_m[at],
                                                                res.centerline_R_WB[at])});
      continue;
    }
    // From the last sample before s (in s's piece: the knots are samples) on to s.
    const auto k =
        static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), probe.s_m) - s.begin()) - 1;
    yp = sample_states[k];
    if (!output_level->integrate_between(rhs, L, s[k], probe.s_m, yp)) return false;
    layout->embed_state(yp, y3);
    const Mat3 R = Eigen::Map<const Mat3>(y3.data() + kR);
    res.probes.push_back({probe.name, rod::probe_position_W_m(probe, y3.segment<3>(kP), R)});
  }
  return true;
}

// ---------------------------------------------------------------------------------------
ShootingSolver::ShootingSolver(const rod::RodModel& model, const Options& options)
    : impl_(std::make_unique<Impl>(model, options, internal::make_3d_layout())) {
  if (!model.obstacles.empty()) return;  // the planar reduction carries no multipliers
  if (auto layout = internal::make_planar_layout(model, impl_->options)) {
    reduced_ = std::make_unique<Impl>(model, options, std::move(layout));
  }
}
ShootingSolver::~ShootingSolver() = default;
ShootingSolver::ShootingSolver(ShootingSolver&&) noexcept = default;

Summary ShootingSolver::solve(const rod::Loads& actuation, Solution& solution) {
  if (actuation.load_scale != 1.0) return solve(actuation.applied(impl_->model), solution);
  // The reduced layout (the planar reduction) solves what it admits, the 3-D one the rest.
  Impl& solver = reduced_ && reduced_->layout->admits(actuation, solution) ? *reduced_ : *impl_;
  return solver.solve(actuation, solution);
}

namespace {

/// Whether the planar reduction's IVP from `sol` is the 3-D one restricted to the plane: the
/// loads stay in the plane and the 3-D unknowns lie in it (their out-of-plane components are
/// zero, so reducing and embedding them gives them back).
bool in_plane(const internal::Layout& planar, const rod::Loads& act, const Solution& sol) {
  if (!planar.admits(act, sol)) return false;
  Eigen::VectorXd x = sol.unknowns;
  planar.reduce_unknowns(x);
  if (x.size() == sol.unknowns.size()) return false;  // not the 3-D unknowns
  planar.embed_unknowns(x);
  return x == sol.unknowns;
}

}  // namespace

rod::Result ShootingSolver::make_result(const rod::Loads& actuation, const Solution& solution,
                                        const Summary& summary) {
  if (actuation.load_scale != 1.0) {
    return make_result(actuation.applied(impl_->model), solution, summary);
  }
  // A solution in the plane is sampled by the planar IVP: the same discretization (the
  // samples agree with the 3-D IVP's to round-off, docs/conventions.md "Planar reduction")
  // at about a third of the cost (the 3-D sampling was more than half of a warm sweep step).
  Impl& sampler = reduced_ && in_plane(*reduced_->layout, actuation, solution) ? *reduced_ : *impl_;
  rod::Result res = sampler.make_result(actuation, solution, summary);
  res.status = to_string(summary.status);
  if (solution.unknowns.size() == impl_->nx && solution.unknowns.allFinite() &&
      res.actuators.size() == impl_->model.actuators.size()) {
    res.base_reaction = impl_->base_reaction(solution.unknowns, res);
  }
  res.residual = summary.equilibrium_residual;
  res.characteristic_force_N = summary.characteristic_force_N;
  rod::check_between_contact_points(impl_->model, res);
  return res;
}

Eigen::VectorXd ShootingSolver::initial_guess(const rod::Loads& actuation) {
  return impl_->initial_guess(actuation, 1.0, true);
}

bool ShootingSolver::residual(const rod::Loads& actuation, const Eigen::VectorXd& x,
                              Eigen::VectorXd& r) {
  return impl_->residual(actuation, 1.0, x, r);
}

bool ShootingSolver::jacobian(const rod::Loads& actuation, const Eigen::VectorXd& x,
                              Eigen::MatrixXd& J) {
  Eigen::VectorXd r0;
  if (impl_->options.jacobian == JacobianMethod::kSensitivity) {
    return impl_->residual_and_jacobian(actuation, 1.0, x, r0, J);
  }
  if (!impl_->residual(actuation, 1.0, x, r0)) return false;
  return impl_->fd_jacobian(actuation, 1.0, x, r0, J);
}

bool ShootingSolver::residual_and_tip_state(const rod::Loads& actuation, const Eigen::VectorXd& x,
                                            Eigen::VectorXd& r, Eigen::VectorXd& tip_state) {
  if (!impl_->residual(actuation, 1.0, x, r)) return false;
  tip_state = impl_->y;
  return true;
}

bool ShootingSolver::tip_sensitivities(const rod::Loads& actuation, const Eigen::VectorXd& x,
                                       Eigen::VectorXd& r, Eigen::MatrixXd& J,
                                       Eigen::VectorXd& tip_state, Eigen::MatrixXd& dtip_dx) {
  if (impl_->options.jacobian != JacobianMethod::kSensitivity) return false;
  if (!impl_->residual_and_jacobian(actuation, 1.0, x, r, J)) return false;
  const int dim = impl_->dim, nx = impl_->nx;
  tip_state = impl_->y;
  dtip_dx.resize(dim, nx);
  for (int j = 0; j < nx; ++j) dtip_dx.col(j) = impl_->Y.segment(dim * (j + 1), dim);
  return true;
}

int ShootingSolver::state_dimension() const { return impl_->dim; }
int ShootingSolver::unknown_count() const { return impl_->nx; }
double ShootingSolver::characteristic_force_N() const { return impl_->Fc; }
const Options& ShootingSolver::options() const { return impl_->options; }

rod::Result solve(const rod::RodModel& model, const Options& options) {
  ShootingSolver solver(model, options);
  const rod::Loads act = rod::Loads::from_model(model);
  Solution sol;
  const Summary summary = solver.solve(act, sol);
  return solver.make_result(act, sol, summary);
}

}  // namespace tcasim::cosserat
