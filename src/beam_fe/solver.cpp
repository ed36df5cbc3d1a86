// Newton's method with backtracking line search and adaptive load stepping.
#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <string>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/internal/klu_refactoring.hpp"
#include "beam_fe/internal/umfpack_loader.hpp"
#include "common/error.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;

/// Backtracking halvings before a Newton step counts as failed.
constexpr int kMaxBacktracks = 12;
/// Residual contraction per iteration (inf norms) below which the next steps reuse the last
/// factorization (chord steps): Newton is then in its quadratic phase, and a chord step
/// contracts by about the relative size of the last Newton correction.
constexpr double kChordContraction = 1e-2;
/// Grow the load increment after a step converging within this many iterations (not
/// counting those that changed the contact set).
constexpr int kEasyIterations = 4;

/// UMFPACK through its plugin (umfpack_plugin_abi.hpp): one factorization object, which
/// analyses the pattern on its first factorization.
class UmfpackFactorization {
 public:
  /// Loads the plugin if needed (InputError when it cannot be loaded).
  UmfpackFactorization() : plugin_(umfpack_plugin()), lu_(plugin_.create()) {
    if (lu_ == nullptr) throw std::bad_alloc();
  }
  UmfpackFactorization(const UmfpackFactorization&) = delete;
  UmfpackFactorization& operator=(const UmfpackFactorization&) = delete;
  ~UmfpackFactorization() { plugin_.destroy(lu_); }
  /// Factorizes K (compressed); false on failure.
  bool factorize(const SpMat& K) {
    assert(K.isCompressed());
    return plugin_.factorize(lu_, static_cast<int>(K.rows()), static_cast<int>(K.nonZeros()),
                             K.outerIndexPtr(), K.innerIndexPtr(), K.valuePtr()) == 1;
  }
  /// Solves K x = b with the last factorization; false on failure.
  bool solve(const VectorXd& b, VectorXd& x) {
    x.resize(b.size());
    return plugin_.solve(lu_, static_cast<int>(b.size()), b.data(), x.data()) == 1;
  }

 private:
  const tcasim_umfpack_plugin& plugin_;
  void* lu_;
};

/// The three sparse LU back ends behind one interface; the pattern is analysed once.
class LinearSystem {
 public:
  explicit LinearSystem(LinearSolver kind) : kind_(kind) {
    if (kind_ == LinearSolver::kUmfpack) umf_ = std::make_unique<UmfpackFactorization>();
  }
  /// Factorizes K (analysing its pattern on the first call); false on failure.
  bool factorize(SpMat& K) {
    switch (kind_) {
      case LinearSolver::kKlu:
        return klu_.factorize(K);
      case LinearSolver::kUmfpack:
        return umf_->factorize(K);
      case LinearSolver::kSparseLu:
        if (!analysed_) slu_.analyzePattern(K);
        analysed_ = true;
        slu_.factorize(K);
        return slu_.info() == Eigen::Success;
    }
    return false;
  }
  /// Solves K x = b with the last factorization; false on failure.
  bool solve(const VectorXd& b, VectorXd& x) {
    switch (kind_) {
      case LinearSolver::kKlu:
        x = b;
        return klu_.solve(x);
      case LinearSolver::kUmfpack:
        return umf_->solve(b, x);
      case LinearSolver::kSparseLu:
        x = slu_.solve(b);
        return slu_.info() == Eigen::Success;
    }
    return false;
  }

 private:
  LinearSolver kind_;
  bool analysed_ = false;
  internal::KluRefactoring klu_;
  std::unique_ptr<UmfpackFactorization> umf_;  ///< kUmfpack only
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> slu_;
};

bool state_matches(const Discretization& disc, const State& st) {
  return static_cast<int>(st.p_W_m.size()) == disc.node_count() &&
         static_cast<int>(st.q_WB.size()) == disc.node_count() &&
         st.s_m.size() == st.p_W_m.size() && st.tensions_N.size() == disc.model().actuators.size();
}

/// Outcome of Newton's method at one load factor.
struct StepResult {
  bool converged = false;
  int iterations = 0;
  double residual_inf = 0.0;
  double scale = 0.0;
  std::string why;
  VectorXd residual;  ///< r at the converged state (empty otherwise)
  /// Failed because the contact set changed more than Options::max_contact_changes times;
  /// `st` then holds the last iterate.
  bool contact_not_settled = false;
  int contact_changes = 0;  ///< iterations that changed the contact set
};

/// The residual (and tangent); false where the state leaves the model's domain (a
/// TCA stretched past its fiber length: DomainError) or the result is not finite.
bool evaluate(const Discretization& disc, const LoadCase& loads, const State& st, double lambda,
              SpMat* K, VectorXd& r, std::string* why = nullptr,
              Discretization::ContactRows rows = Discretization::ContactRows::kComplementarity) {
  try {
    r = disc.residual(st, loads, lambda, K, rows);
  } catch (const DomainError& e) {
    if (why) *why = e.what();
    return false;
  }
  if (!r.allFinite() && why) *why = "the residual is not finite";
  return r.allFinite();
}

StepResult newton(const Discretization& disc, const LoadCase& loads, const Options& options,
                  double lambda, State& st, SpMat& K, LinearSystem& linear) {
  StepResult out;
  disc.apply_prescribed_tensions(loads, st, lambda);
  VectorXd r;
  if (!evaluate(disc, loads, st, lambda, &K, r, &out.why)) return out;
  bool have_tangent = true;  // K is the tangent at st
  bool factored = false;     // `linear` holds a factorization of an earlier tangent of this step
  double contraction = std::numeric_limits<double>::infinity();  // ||r_k||/||r_k-1||, inf norms
  for (int it = 0;; ++it) {
    out.residual_inf = r.lpNorm<Eigen::Infinity>();
    out.scale = disc.residual_scale(st, loads, lambda);
    if (disc.within_tolerance(r, st, loads, lambda, options)) {
      out.converged = true;
      out.residual = std::move(r);
      return out;
    }
    if (it == options.max_iterations) {
      out.why = fmt::format("no convergence in {} Newton iterations (||r||_inf = {:.3e})",
                            options.max_iterations, out.residual_inf);
      return out;
    }
    ++out.iterations;
    // Quasi-Newton (chord) acceptance: once the residual contracts by kChordContraction per
    // iteration, the previous factorization is reused and trial residuals are evaluated
    // without the tangent; a poorer contraction brings the full Newton step back.
    const bool chord = factored && !have_tangent && contraction <= kChordContraction;
    if (!chord) {
      if (!have_tangent && !evaluate(disc, loads, st, lambda, &K, r, &out.why)) return out;
      have_tangent = true;
      if (!linear.factorize(K)) {
        out.why = "the tangent matrix could not be factorized (singular or not finite)";
        return out;
      }
      factored = true;
    }
    VectorXd dx;
    if (!linear.solve(-r, dx) || !dx.allFinite()) {
      out.why = "the linear solve failed (singular or not finite)";
      return out;
    }
    // Line search as a safeguard: full Newton steps are taken whenever the trial state is
    // inside the model's domain with a finite residual; otherwise the step is halved. Tests
    // of sufficient decrease (|r| or the natural monotonicity test) were tried and reject
    // the good overshooting first steps of beams (a straight rod's first iterate raises |r|
    // up to 1e6-fold before Newton converges quadratically), stalling Newton at small
    // alpha; globalization is by the load stepping instead: a step that does not converge
    // within max_iterations is halved.
    // The trial's tangent is assembled with its residual (an accepted Newton step then
    // needs no second evaluation) unless the contraction says the next step is a chord step.
    const bool trial_tangent = contraction > kChordContraction;
    double alpha = 1.0;
    bool accepted = false;
    std::string trial_why;
    for (int b = 0; b <= kMaxBacktracks; ++b, alpha *= 0.5) {
      State trial = st;
      disc.retract(trial, alpha * dx);
      VectorXd rt;
      if (!evaluate(disc, loads, trial, lambda, trial_tangent ? &K : nullptr, rt, &trial_why))
        continue;
      st = std::move(trial);
      contraction = rt.lpNorm<Eigen::Infinity>() /
                    std::max(out.residual_inf, std::numeric_limits<double>::min());
      r = std::move(rt);
      have_tangent = trial_tangent;
      accepted = true;
      break;
    }
    if (!accepted) {
      out.why = "every backtracked Newton step failed: " + trial_why;
      return out;
    }
  }
}

/// mu_P = -W_PP^-1 q_P on the pairs P (zero elsewhere); false when not finite.
bool solve_on(const Eigen::MatrixXd& W, const VectorXd& q, const std::vector<int>& P, VectorXd& z) {
  z = VectorXd::Zero(q.size());
  if (P.empty()) return true;
  const int f = static_cast<int>(P.size());
  Eigen::MatrixXd W_PP(f, f);
  VectorXd q_P(f);
  for (int a = 0; a < f; ++a) {
    q_P[a] = q[P[a]];
    for (int b = 0; b < f; ++b) W_PP(a, b) = W(P[a], P[b]);
  }
  const VectorXd z_P = Eigen::PartialPivLU<Eigen::MatrixXd>(W_PP).solve(-q_P);
  if (!z_P.allFinite()) return false;
  for (int a = 0; a < f; ++a) z[P[a]] = z_P[a];
  return true;
}

/// Solves the linear complementarity problem mu >= 0, w = W mu + q >= 0, mu . w = 0, i.e. the
/// bound-constrained quadratic program min 1/2 mu^T W mu + q^T mu, mu >= 0 for the (nearly
/// symmetric, positive definite) W = D K^-1 G^T, by a primal active-set method in the manner
/// of Lawson and Hanson's NNLS: mu stays feasible; the pair with the most negative w joins the
/// closed pairs P, mu moves toward the minimizer on P and stops where a multiplier reaches 0
/// (that pair leaves P). Each change lowers the objective, so no set repeats (finite for a
/// positive definite W). Warm start: P = the pairs `closed` marks, less those whose multiplier
/// on P comes out <= 0. Returns the closed pairs in `closed`; false when 3 c + 50 changes pass
/// or a solve is not finite.
bool solve_lcp(const Eigen::MatrixXd& W, const VectorXd& q, double eps_w, std::vector<char>& closed,
               VectorXd& mu) {
  const int c = static_cast<int>(q.size());
  std::vector<int> P;
  for (int i = 0; i < c; ++i)
    if (closed[i]) P.push_back(i);
  VectorXd z;
  while (true) {
    if (!solve_on(W, q, P, z)) return false;
    std::vector<int> kept;
    for (const int i : P)
      if (z[i] > 0.0) kept.push_back(i);
    if (kept.size() == P.size()) break;
    P = std::move(kept);
  }
  mu = z;
  for (int change = 0; change < 3 * c + 50; ++change) {
    const VectorXd w = W * mu + q;
    std::vector<char> in(static_cast<std::size_t>(c), 0);
    for (const int i : P) in[i] = 1;
    int worst = -1;
    for (int i = 0; i < c; ++i)
      if (!in[i] && w[i] < -eps_w && (worst < 0 || w[i] < w[worst])) worst = i;
    if (worst < 0) {
      closed.assign(static_cast<std::size_t>(c), 0);
      for (const int i : P) closed[i] = 1;
      return true;
    }
    P.push_back(worst);
    while (true) {
      if (!solve_on(W, q, P, z)) return false;
      double alpha = 1.0;
      for (const int i : P)
        if (z[i] <= 0.0) alpha = std::min(alpha, mu[i] > z[i] ? mu[i] / (mu[i] - z[i]) : 0.0);
      mu += alpha * (z - mu);
      if (alpha == 1.0) break;
      std::vector<int> kept;
      for (const int i : P) {
        if (z[i] <= 0.0 && mu[i] <= 0.0 + 1e-15 * std::abs(mu.maxCoeff())) {
          mu[i] = 0.0;
        } else {
          kept.push_back(i);
        }
      }
      if (kept.size() == P.size()) {
        // The step's limiting pair: drop it.
        int limiting = -1;
        for (const int i : P)
          if (z[i] <= 0.0 && (limiting < 0 || mu[i] < mu[limiting])) limiting = i;
        mu[limiting] = 0.0;
        kept.erase(std::find(kept.begin(), kept.end(), limiting));
      }
      P = std::move(kept);
      ++change;
    }
  }
  return false;
}

/// The Newton step of the contact problem (docs/conventions.md "Contact in the FE"): the
/// tangent K of every pair open (factorized in `linear`, residual r_open) gives the step
/// dx0 = -K^-1 r_open with every multiplier zero and, per pair j, the response x_j = K^-1 e_j
/// to a unit multiplier (its force G_j on its node); the linearized gaps are b + W mu with b_i
/// = g_i + D_i dx0 and W_ij = D_i x_j (D_i = dg_i/dx by central differences), and the new
/// multipliers mu solve that complementarity problem exactly (solve_lcp): dx = dx0 + sum_j
/// mu_j x_j. Only the pairs closed now (or, with none, the deepest penetration at dx0) enter
/// the dense problem at first; the pairs left out whose linearized gaps come out negative join
/// and the problem is solved again. False (with `why`) when a solve fails or the pivoting does not
/// end.
bool contact_step(const Discretization& disc, const Options& options, const State& st,
                  const VectorXd& r_open, LinearSystem& linear, VectorXd& dx, std::string& why) {
  const int n = disc.dof_count(), m = disc.contact_count(), first = n - m;
  VectorXd dx0;
  if (!linear.solve(-r_open, dx0) || !dx0.allFinite()) {
    why = "the linear solve failed (singular or not finite)";
    return false;
  }
  VectorXd b(m);
  std::vector<Eigen::Matrix<double, 1, 6>> D(static_cast<std::size_t>(m));
  Discretization::ContactBlock block;
  const int per_node = disc.contact_pairs_per_node(), n_cand = disc.contact_candidates();
  for (int j = 0; j < m; ++j) {
    const int node = disc.contact_node(j);
    const int in_node = j % per_node;
    const auto c = static_cast<std::size_t>(in_node % n_cand);
    if (c == 0) disc.contact_block(st, node, in_node / n_cand, true, block);
    D[j] = block.dg[c];
    const double g = block.pair[c].gap_m;
    b[j] = g + D[j].transpose().dot(dx0.segment<6>(6 * (node - 1)));
  }
  // Feasibility tolerance of a linearized gap: a tenth of the convergence test's absolute
  // tolerance and round-off floor of a force row, over k.
  const double eps_w =
      0.1 * (options.tolerance_abs + disc.round_off_floor().force) / disc.contact_stiffness_N_m();
  std::vector<int> pairs;  // the pairs of the dense problem
  std::vector<char> in(static_cast<std::size_t>(m), 0);
  // Start from the closed pairs, or without any from the deepest penetration at dx0: the
  // pairs it holds off need no column of their own (each column is a back-substitution).
  int deepest = -1;
  for (int j = 0; j < m; ++j) {
    if (st.contact_lambda_N[j] > 0.0) {
      pairs.push_back(j);
      in[j] = 1;
    }
    if (b[j] < eps_w && (deepest < 0 || b[j] < b[deepest])) deepest = j;
  }
  if (pairs.empty() && deepest >= 0) {
    pairs.push_back(deepest);
    in[deepest] = 1;
  }
  std::vector<VectorXd> x(static_cast<std::size_t>(m));
  VectorXd mu;
  while (true) {
    for (const int j : pairs) {
      if (x[j].size() > 0) continue;
      VectorXd unit = VectorXd::Zero(n);
      unit[first + j] = 1.0;
      if (!linear.solve(unit, x[j]) || !x[j].allFinite()) {
        why = "the linear solve failed (singular or not finite)";
        return false;
      }
    }
    const int c = static_cast<int>(pairs.size());
    Eigen::MatrixXd W(c, c);
    VectorXd q(c);
    std::vector<char> closed(static_cast<std::size_t>(c));
    for (int a = 0; a < c; ++a) {
      const int i = pairs[a], node_i = 6 * (disc.contact_node(i) - 1);
      q[a] = b[i];
      closed[a] = st.contact_lambda_N[i] > 0.0;
      for (int c2 = 0; c2 < c; ++c2)
        W(a, c2) = D[i].transpose().dot(x[pairs[c2]].segment<6>(node_i));
    }
    if (!solve_lcp(W, q, eps_w, closed, mu)) {
      why = fmt::format("the linearized contact problem of {} pairs did not settle", c);
      return false;
    }
    bool grown = false;
    for (int j = 0; j < m; ++j) {
      if (in[j]) continue;
      const int node_j = 6 * (disc.contact_node(j) - 1);
      double w = b[j];
      for (int a = 0; a < c; ++a) w += D[j].transpose().dot(x[pairs[a]].segment<6>(node_j)) * mu[a];
      if (w < -eps_w) {
        pairs.push_back(j);
        in[j] = 1;
        grown = true;
      }
    }
    if (!grown) break;
  }
  dx = dx0;
  for (std::size_t a = 0; a < pairs.size(); ++a)
    dx += mu[static_cast<Eigen::Index>(a)] * x[pairs[a]];
  return true;
}

/// Newton's method with obstacles at one load factor: every iteration solves the contact
/// problem linearized at the iterate exactly (contact_step), so the contact set of the next
/// iterate is that of the linearized problem; the set (State::contact_lambda_N's pairs with
/// lambda - k g > 0) settles as Newton converges. Converged when the complementarity residual
/// (ContactRows::kComplementarity) is within tolerance and the last step left the set
/// unchanged; a step that changes it more than Options::max_contact_changes times fails with
/// contact_not_settled. No chord steps (the set may change with every tangent).
StepResult newton_contact(const Discretization& disc, const LoadCase& loads, const Options& options,
                          double lambda, State& st, SpMat& K, LinearSystem& linear) {
  using Rows = Discretization::ContactRows;
  StepResult out;
  disc.apply_prescribed_tensions(loads, st, lambda);
  VectorXd r;
  if (!evaluate(disc, loads, st, lambda, nullptr, r, &out.why)) return out;
  std::vector<char> set = disc.contact_set(st);
  bool set_changed = false;  // the last step changed the contact set
  for (int it = 0;; ++it) {
    out.residual_inf = r.lpNorm<Eigen::Infinity>();
    out.scale = disc.residual_scale(st, loads, lambda);
    if (!set_changed && disc.within_tolerance(r, st, loads, lambda, options)) {
      out.converged = true;
      out.residual = std::move(r);
      return out;
    }
    if (set_changed && ++out.contact_changes > options.max_contact_changes) {
      out.contact_not_settled = true;
      out.why = fmt::format(
          "the contact set did not settle: {} Newton iterations changed it (max_contact_changes "
          "= {}; ||r||_inf = {:.3e})",
          out.contact_changes, options.max_contact_changes, out.residual_inf);
      return out;
    }
    if (it == options.max_iterations) {
      out.why = fmt::format("no convergence in {} Newton iterations (||r||_inf = {:.3e})",
                            options.max_iterations, out.residual_inf);
      return out;
    }
    ++out.iterations;
    VectorXd r_open;
    if (!evaluate(disc, loads, st, lambda, &K, r_open, &out.why, Rows::kOpen)) return out;
    if (!linear.factorize(K)) {
      out.why = "the tangent matrix could not be factorized (singular or not finite)";
      return out;
    }
    VectorXd dx;
    if (!contact_step(disc, options, st, r_open, linear, dx, out.why)) return out;
    // Backtracking only out of the model's domain, as in newton.
    double alpha = 1.0;
    bool accepted = false;
    std::string trial_why;
    for (int bt = 0; bt <= kMaxBacktracks; ++bt, alpha *= 0.5) {
      State trial = st;
      disc.retract(trial, alpha * dx);
      VectorXd rt;
      if (!evaluate(disc, loads, trial, lambda, nullptr, rt, &trial_why)) continue;
      st = std::move(trial);
      r = std::move(rt);
      accepted = true;
      break;
    }
    if (!accepted) {
      out.why = "every backtracked Newton step failed: " + trial_why;
      return out;
    }
    std::vector<char> next = disc.contact_set(st);
    set_changed = next != set;
    set = std::move(next);
  }
}

/// Summary::equilibrium_residual of the residual r at load factor 1.
double equilibrium_residual(const Discretization& disc, const VectorXd& r, double F_c) {
  const int free_dofs = 6 * (disc.node_count() - 1);
  const double L = disc.model().length_m;
  double force = 0.0;
  for (int i = 0; i < r.size(); ++i) {
    const bool moment_row = i < free_dofs && i % 6 >= 3;
    force = std::max(force, std::abs(r[i]) / (moment_row ? L : 1.0));
  }
  return force / F_c;
}

}  // namespace

const char* to_string(Summary::Status s) {
  switch (s) {
    case Summary::Status::kConverged:
      return "converged";
    case Summary::Status::kStepTooSmall:
      return "step_too_small";
    case Summary::Status::kLoadStepLimit:
      return "load_step_limit";
    case Summary::Status::kContactNotSettled:
      return "contact_not_settled";
    case Summary::Status::kNotRun:
      return "not_run";
  }
  return "unknown";
}

Summary solve(const rod::RodModel& model, const Options& options, State& state) {
  return solve(model, rod::Loads::from_model(model), options, state);
}

Summary solve(const rod::RodModel& model, const rod::Loads& loads, const Options& options,
              State& state) {
  return Solver(model, options).solve(loads, state);
}

Solver::Solver(const rod::RodModel& model, const Options& options)
    : model_(&model), options_(options), disc_(model, options) {}

Summary Solver::solve(const rod::Loads& loads_in, State& state) const {
  const auto t0 = std::chrono::steady_clock::now();
  const rod::RodModel& model = *model_;
  const Options& options = options_;
  const Discretization& disc = disc_;
  Summary summary;
  const LoadCase loads = disc.load_case(loads_in);  // validates the loads
  if (!state_matches(disc, state)) state = disc.reference_state();
  if (static_cast<int>(state.contact_lambda_N.size()) != disc.contact_count()) {
    // A state of the same mesh without (these) obstacles: every pair starts open.
    state.contact_lambda_N.assign(static_cast<std::size_t>(disc.contact_count()), 0.0);
  }
  auto finish = [&](Summary& s) -> Summary {
    s.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  };
  SpMat K;
  LinearSystem linear(options.linear_solver);
  // A fresh start from the unloaded state takes the constant-strain predictor when it applies.
  bool from_reference = state.load_factor == 0.0;
  double lambda = state.load_factor >= 1.0 ? 1.0 : state.load_factor;
  double step = std::min(options.initial_load_step, 1.0 - lambda);
  int attempts = 0;
  StepResult last;
  State unsettled;  // the last iterate of the last step whose contact set did not settle
  // The last two accepted states: their secant extrapolates the next load step's start.
  State previous;
  double lambda_previous = -1.0;
  bool use_predictor = true;
  if (lambda >= 1.0) step = 0.0;  // warm start at full load: one Newton solve at lambda = 1
  while (true) {
    if (attempts == options.max_load_steps) {
      summary.status = Summary::Status::kLoadStepLimit;
      summary.message = fmt::format("{} load steps reached load factor {:.6g} < 1",
                                    options.max_load_steps, lambda);
      break;
    }
    ++attempts;
    const double target = step > 0.0 ? std::min(1.0, lambda + step) : 1.0;
    State trial = state;
    bool predicted = false;
    if (use_predictor && step > 0.0) {
      if (from_reference) {
        predicted = disc.constant_strain_guess(loads, target, trial);
      } else if (lambda_previous >= 0.0 && lambda > lambda_previous) {
        // Secant predictor: x(target) ~ x(lambda) + (target - lambda)/(lambda - lambda_prev) dx.
        disc.retract(trial, (target - lambda) / (lambda - lambda_previous) *
                                disc.difference(state, previous));
        predicted = true;
      }
    }
    last = disc.contact_count() > 0 ? newton_contact(disc, loads, options, target, trial, K, linear)
                                    : newton(disc, loads, options, target, trial, K, linear);
    summary.iterations += last.iterations;
    if (last.contact_not_settled) {
      unsettled = trial;
      unsettled.load_factor = target;
    }
    if (last.converged) {
      previous = std::move(state);
      lambda_previous = lambda;
      state = std::move(trial);
      state.load_factor = target;
      lambda = target;
      from_reference = false;
      use_predictor = true;
      ++summary.load_steps;
      summary.residual_inf = last.residual_inf;
      summary.residual_scale = last.scale;
      if (lambda >= 1.0) {
        summary.status = Summary::Status::kConverged;
        break;
      }
      // Iterations that moved the contact set are the active-set search, not a sign of a hard
      // step (none without obstacles).
      if (last.iterations - last.contact_changes <= kEasyIterations) step *= 2.0;
      step = std::min(step, 1.0 - lambda);
      continue;
    }
    ++summary.rejected_steps;
    if (predicted) {
      // Retry the same increment from the last accepted state before halving it.
      use_predictor = false;
      continue;
    }
    use_predictor = true;
    if (step == 0.0) {
      // A warm start at full load failed: ramp again from the reference configuration.
      state = disc.reference_state();
      lambda = 0.0;
      lambda_previous = -1.0;
      from_reference = true;
      step = options.initial_load_step;
      continue;
    }
    step *= 0.5;
    if (step < options.min_load_step || step == 0.0) {
      summary.status = Summary::Status::kStepTooSmall;
      summary.message = fmt::format("load step halved below {:.3g} at load factor {:.6g}: {}",
                                    options.min_load_step, lambda, last.why);
      break;
    }
  }
  if (!summary.converged() && last.contact_not_settled) {
    // The last failure was a contact set that did not settle: report it with its last iterate.
    summary.status = Summary::Status::kContactNotSettled;
    summary.message = fmt::format("at load factor {:.6g}: {}", unsettled.load_factor, last.why);
    state = std::move(unsettled);
    lambda = state.load_factor;
  }
  summary.load_factor = lambda;
  summary.characteristic_force_N = rod::characteristic_force_N(model, loads.loads);
  if (summary.converged()) {
    summary.equilibrium_residual =
        equilibrium_residual(disc, last.residual, summary.characteristic_force_N);
  } else {
    // Report the residual of the returned (last accepted) state at its load factor.
    VectorXd r;
    summary.residual_inf = evaluate(disc, loads, state, state.load_factor, nullptr, r)
                               ? r.lpNorm<Eigen::Infinity>()
                               : std::numeric_limits<double>::infinity();
    if (evaluate(disc, loads, state, 1.0, nullptr, r)) {
      summary.equilibrium_residual = equilibrium_residual(disc, r, summary.characteristic_force_N);
    }
    summary.residual_scale = disc.residual_scale(state, loads, state.load_factor);
    if (!summary.message.empty() && summary.load_steps == 0 && state.load_factor == 0.0) {
      summary.message += " (no load step converged; the state is the reference configuration)";
    }
  }
  return finish(summary);
}

rod::Result make_result(const rod::RodModel& model, const Options& options, const State& state,
                        const Summary& summary) {
  return make_result(model, rod::Loads::from_model(model), options, state, summary);
}

rod::Result make_result(const rod::RodModel& model, const rod::Loads& loads, const Options& options,
                        const State& state, const Summary& summary) {
  return Solver(model, options).make_result(loads, state, summary);
}

rod::Result Solver::make_result(const rod::Loads& loads_in, const State& state,
                                const Summary& summary) const {
  const rod::RodModel& model = *model_;
  const Options& options = options_;
  loads_in.validate(model);
  const rod::Loads loads = loads_in.applied(model);
  rod::Result res;
  res.scenario = model.name;
  res.method = "fe";
  // The mesh's element count (a body that varies along s, string anchors, spline knots or
  // extra knots: aligned to them, as Discretization's constructor builds it).
  res.discretization = {{"elements", disc_.element_count()}, {"order", options.order}};
  res.converged = summary.converged();
  res.status = to_string(summary.status);
  res.iterations = summary.iterations;
  res.residual = summary.equilibrium_residual;
  res.characteristic_force_N = summary.characteristic_force_N;
  res.wall_time_s = summary.wall_time_s;
  res.message = summary.message;
  if (state.p_W_m.empty()) return res;
  res.tip_position_W_m = state.p_W_m.back();
  res.tip_R_WB = state.q_WB.back().toRotationMatrix();
  const Discretization& disc = disc_;
  const std::vector<double> lengths = disc.string_lengths(state);
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    rod::ActuatorResult a;
    a.name = model.actuators[i].name;
    a.tension_N = state.tensions_N[i];
    a.elongation_m = lengths[i] - model.actuators[i].rest_length_m;
    rod::set_coil_contacts(model.actuators[i], loads.actuators[i].segments, a);
    res.actuators.push_back(std::move(a));
  }
  if (model.tip_constraint) res.tip_reaction_force_W_N = state.tip_reaction_W_N;
  res.centerline_s_m = state.s_m;
  res.centerline_p_W_m = state.p_W_m;
  for (const Eigen::Quaterniond& q : state.q_WB)
    res.centerline_R_WB.push_back(q.toRotationMatrix());
  res.probes = probe_results(disc, state);
  res.base_reaction = disc.base_reaction(state, disc.load_case(loads_in), state.load_factor);
  for (std::size_t o = 0; o < model.obstacles.size(); ++o) {
    res.contacts.push_back(rod::summarize_contact(model.obstacles[o],
                                                  disc.contact_samples(state, static_cast<int>(o)),
                                                  model.base_position_W_m));
  }
  try {
    res.bending_radius_m = rod::three_point_inner_radius(model, res.centerline_s_m,
                                                         res.centerline_p_W_m, res.centerline_R_WB);
  } catch (const DomainError&) {
    // A custom section has no outline: the radius metric is undefined, left empty.
    res.bending_radius_m.reset();
  }
  rod::check_between_contact_points(model, res);
  return res;
}

}  // namespace tcasim::beam_fe
