// Frictionless contact with rigid obstacles (docs/conventions.md "Contact in the shooting
// method"): the contact grid, the IVP with the contact point forces at its nodes, the
// primal-dual active-set Newton iteration on (x, lambda_A) and the contact results.
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "cosserat/internal/shooting_impl.hpp"

namespace tcasim::cosserat {

using namespace stage_names;

namespace {

/// Armijo constant of the backtracking line search on ||F||^2 / 2 (as newton.cpp's).
constexpr double kArmijo = 1e-4;
/// Relative forward-difference step sqrt(eps) of the Jacobian columns.
constexpr double kForwardStep = 1.4901161193847656e-08;
/// Scaled residual of the iteration on one active set below which the set is updated
/// (about sqrt of the tolerance: Newton is then a step or two from the end).
constexpr double kSettledResidual = 1e-5;
/// ... or after this many Newton steps on one set (a set whose own solution is far, e.g. two
/// adjacent nodes on a curved obstacle pulling and pushing, converges slowly).
constexpr int kMaxStepsPerSet = 4;
/// Largest motion of a node in one step of the cold continuation, over L (contact_solve).
constexpr double kMaxStepMotion = 0.25;

/// Half the thickness of an obstacle (half its radius, or of its smallest half extent; a
/// plane's half-space is infinitely thick): a node that moves less than its clearance plus
/// this cannot have passed through it.
double half_thickness_m(const rod::Obstacle& ob) {
  double t = std::numeric_limits<double>::infinity();  // a plane's half-space
  if (ob.type == rod::Obstacle::Type::kCylinder || ob.type == rod::Obstacle::Type::kSphere)
    t = ob.radius_m;
  if (ob.type == rod::Obstacle::Type::kBox) t = ob.half_extents_m.minCoeff();
  return 0.5 * t;
}

}  // namespace

void ShootingSolver::Impl::build_contact_grid() {
  ContactGrid& g = contact_grid;
  g = ContactGrid();
  g.n_obs = static_cast<int>(model.obstacles.size());
  g.n_cand = 1;
  const int steps = options.integrator.steps;
  g.s.push_back(0.0);
  g.knot.push_back(-1);
  if (knots.empty()) {
    for (int k = 1; k <= steps; ++k) {
      g.s.push_back(k == steps ? L : k * (L / steps));
      g.piece.push_back(0);
      g.knot.push_back(-1);
    }
  } else {
    // The step nodes of IntegrationLevel's pieces: steps x (piece length) / L equal steps
    // per piece, at least one.
    for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
      const double lo = knots[i], hi = knots[i + 1];
      const int n = std::max(1, static_cast<int>(std::lround(steps * (hi - lo) / L)));
      for (int j = 1; j <= n; ++j) {
        g.s.push_back(j == n ? hi : lo + j * ((hi - lo) / n));
        g.piece.push_back(static_cast<int>(i));
        g.knot.push_back(j == n && i + 2 < knots.size() ? static_cast<int>(i + 1) : -1);
      }
    }
  }
  for (std::size_t k = 0; k < g.s.size(); ++k) {
    // The outline of the section at the node (at the tip, the limit from the left).
    g.outline.push_back(rod::contact_outline_at(
        model, g.s[k], k + 1 == g.s.size() ? rod::Side::kLeft : rod::Side::kRight));
    g.n_cand = std::max(g.n_cand, rod::contact_candidate_count(g.outline.back().kind));
  }
  ode::IntegratorOptions one = options.integrator;
  one.steps = 1;
  one.output_intervals = 0;
  contact_step.emplace(dim, one);
}

bool ShootingSolver::Impl::contact_ivp(const rod::Loads& act, const Eigen::VectorXd& x,
                                       const std::vector<double>& lam, int from, ContactIvp& iv,
                                       const ode::Observer* observer) {
  const ContactGrid& g = contact_grid;
  const int n = static_cast<int>(g.s.size()) - 1;
  if (!all_finite(x)) return false;
  set_parameters(act, contact_fraction, x);
  iv.y_node.resize(static_cast<std::size_t>(n + 1));
  iv.gap.resize(static_cast<std::size_t>(g.pairs()));
  if (from == 0) {
    iv.y_node[0].resize(dim);
    initial_state(x, iv.y_node[0]);
  }
  y = iv.y_node[static_cast<std::size_t>(from)];
  ++ivp_count;
  const bool pieces_on = piece_hooks() != nullptr;
  auto enter = [&](int piece_index) {
    if (pieces_on) pieces.enter(knots[piece_index], knots[piece_index + 1]);
  };
  enter(g.piece[static_cast<std::size_t>(from == 0 ? 0 : from - 1)]);
  for (int k = from;; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    if (k > from) iv.y_node[ku] = y;
    if (k > 0) {
      // The contact forces of the node's pairs, at the pose of the node (continuous).
      const Vec3 p = y.segment<3>(kP);
      const Mat3 R = Eigen::Map<const Mat3>(y.data() + kR);
      Vec3 f = Vec3::Zero(), m = Vec3::Zero();
      for (int o = 0; o < g.n_obs; ++o) {
        candidates =
            rod::section_gaps(model.obstacles[static_cast<std::size_t>(o)], g.outline[ku], p, R);
        for (int j = 0; j < g.n_cand; ++j) {
          const auto pair = static_cast<std::size_t>((k - 1) * g.per_node() + o * g.n_cand + j);
          rod::SectionGap& sg = iv.gap[pair];
          if (j < static_cast<int>(candidates.size())) {
            sg = candidates[static_cast<std::size_t>(j)];
          } else {  // a section with fewer candidates than the grid's slots: open
            sg = rod::SectionGap();
            sg.gap_m = std::numeric_limits<double>::infinity();
          }
          if (lam[pair] == 0.0) continue;
          const Vec3 F = lam[pair] * sg.normal_W;
          f += F;
          m += sg.offset_W_m.cross(F);
        }
      }
      if (!f.isZero(0.0) || !m.isZero(0.0)) {
        if (!point_wrench_jump(g.s[ku], R.transpose() * f, R.transpose() * m, y)) return false;
      }
      if (g.knot[ku] >= 0) {
        enter(g.piece[ku]);
        if (!pieces.jump(static_cast<std::size_t>(g.knot[ku]), y)) return false;
      }
    }
    if (observer) (*observer)(g.s[ku], y);
    if (k == n) break;
    const ode::IntegrationSummary is = contact_step->integrate(rhs, g.s[ku], g.s[ku + 1], y);
    if (is.status != ode::IntegrationSummary::Status::kSuccess || !y.allFinite()) return false;
  }
  return tip_residual(act, contact_fraction, x, y, iv.r);
}

namespace {

/// The active-set residual F = (r, g_A / L) (pairs in `active` order).
void stack_residual(const Eigen::VectorXd& r, const std::vector<rod::SectionGap>& gap,
                    const std::vector<int>& active, double L, Eigen::VectorXd& F) {
  const auto nx = r.size();
  F.resize(nx + static_cast<Eigen::Index>(active.size()));
  F.head(nx) = r;
  for (std::size_t a = 0; a < active.size(); ++a) {
    F[nx + static_cast<Eigen::Index>(a)] = gap[static_cast<std::size_t>(active[a])].gap_m / L;
  }
}

}  // namespace

Summary::Status ShootingSolver::Impl::active_set_newton(const rod::Loads& act, Eigen::VectorXd& x,
                                                        std::vector<double>& lam, Summary& summary,
                                                        std::string& why) {
  const ContactGrid& g = contact_grid;
  const int n_pairs = g.pairs();
  const int n_nodes = static_cast<int>(g.s.size()) - 1;  // contact nodes k = 1..n
  const double lam_tol = options.tolerance * Fc;         // a multiplier this negative leaves
  const double gap_tol = options.tolerance * L;          // a gap this negative enters
  if (!contact_ivp(act, x, lam, 0, contact_iv)) {
    why = "the IVP with contact forces failed at the start";
    return Summary::Status::kInitialPointFailed;
  }
  // Half the thickness of each obstacle: how deep a node may go before it must enter the
  // active set, and how far it may move in one step (see `tunnels`).
  std::vector<double> half_thickness;
  for (const rod::Obstacle& ob : model.obstacles) half_thickness.push_back(half_thickness_m(ob));
  // The active-set update (docs/conventions.md "Contact in the shooting method"): of each
  // run of consecutive penetrating open nodes the deepest enters; with `release`, negative
  // multipliers leave (one_per_run: only the most negative of each run of consecutive
  // active nodes).
  auto update_active = [&](const std::vector<char>& in_now, const std::vector<double>& l,
                           const ContactIvp& iv, bool one_per_run, bool release,
                           std::vector<char>& out) {
    out = in_now;
    for (int col = 0; col < g.per_node(); ++col) {  // one obstacle's candidate along s
      int deepest = -1, most_negative = -1;
      for (int k = 0; k <= n_nodes; ++k) {
        const int i = k < n_nodes ? k * g.per_node() + col : -1;
        // Before the set has settled only deep penetrations enter (a quarter of the
        // obstacle's half thickness: it must not be passed through).
        const double depth =
            release ? gap_tol : std::max(gap_tol, 0.25 * half_thickness[col / g.n_cand]);
        const bool violates = i >= 0 && !in_now[i] && iv.gap[i].gap_m < -depth;
        if (violates && (deepest < 0 || iv.gap[i].gap_m < iv.gap[deepest].gap_m)) deepest = i;
        if (!violates && deepest >= 0) {
          out[deepest] = 1;
          deepest = -1;
        }
        const bool on = i >= 0 && in_now[i];
        if (on && !std::isfinite(iv.gap[i].gap_m)) out[i] = 0;  // the candidate vanished
        if (release && on && l[i] < -lam_tol) {
          if (!one_per_run) out[i] = 0;
          if (most_negative < 0 || l[i] < l[most_negative]) most_negative = i;
        }
        if (!on && most_negative >= 0) {
          out[most_negative] = 0;
          most_negative = -1;
        }
      }
    }
  };
  // The starting set: the pairs with lambda > 0 on entry (a warm start), updated.
  std::vector<char> in(static_cast<std::size_t>(n_pairs), 0);
  for (int i = 0; i < n_pairs; ++i) {
    in[i] = lam[i] > 0.0;
    if (!in[i]) lam[i] = 0.0;
  }
  bool changed = false;
  {
    std::vector<char> start;
    update_active(in, lam, contact_iv, false, true, start);
    changed = start != in;
    in = start;
  }
  std::vector<char> recent(static_cast<std::size_t>(n_pairs), 0);  // released last
  int on_this_set = 0;                  // Newton steps since the active set last changed
  std::vector<std::vector<char>> seen;  // the active sets visited (cycle detection)
  bool cautious = false;                // after a cycle: one pair per contiguous zone
  std::vector<int> active;
  Eigen::VectorXd F, Ft, dz, xt;
  Eigen::MatrixXd J;
  std::vector<double> lam_t;
  const Eigen::VectorXd typ = typical_scale();
  // A trial point that moves a node farther than its clearance plus half the obstacle's
  // thickness might have passed through the obstacle (a thin one looks clear from both
  // sides): the line search backs off instead.
  auto tunnels = [&](const ContactIvp& trial, const std::vector<char>& active_now) {
    for (int k = 1; k <= n_nodes; ++k) {
      const double moved = (trial.y_node[static_cast<std::size_t>(k)].segment<3>(kP) -
                            contact_iv.y_node[static_cast<std::size_t>(k)].segment<3>(kP))
                               .norm();
      for (int col = 0; col < g.per_node(); ++col) {
        // An active pair is held on the surface by its own equation.
        if (active_now[(k - 1) * g.per_node() + col]) continue;
        const double clear = std::max(0.0, contact_iv.gap[(k - 1) * g.per_node() + col].gap_m);
        if (moved > clear + half_thickness[static_cast<std::size_t>(col / g.n_cand)]) return true;
      }
    }
    return false;
  };
  for (int it = 0;; ++it) {
    active.clear();
    for (int i = 0; i < n_pairs; ++i) {
      if (in[i]) active.push_back(i);
    }
    const int na = static_cast<int>(active.size());
    stack_residual(contact_iv.r, contact_iv.gap, active, L, F);
    summary.residual = F.lpNorm<Eigen::Infinity>();
    if (!changed && summary.residual <= options.tolerance) return Summary::Status::kConverged;
    if (it >= options.max_iterations) {
      why = "reached max_iterations = " + std::to_string(options.max_iterations) +
            " with scaled residual " + format_value(summary.residual) +
            (changed ? " and the active set of the contact points still changing" : "") +
            (cautious ? " (it cycled)" : "");
      return changed ? Summary::Status::kContactNotSettled : Summary::Status::kMaxIterations;
    }
    // Jacobian by forward differences: x columns re-integrate from s = 0, a multiplier's
    // column from its node (the states before it do not depend on it).
    const int nz = nx + na;
    J.resize(nz, nz);
    for (int j = 0; j < nx; ++j) {
      xt = x;
      xt[j] = x[j] + kForwardStep * std::max(std::abs(x[j]), typ[j]);
      double h = xt[j] - x[j];
      // A forward step can leave the model's domain where the iterate lies on its edge (a
      // TCA law at its limits): the backward difference then, of the same accuracy.
      if (!contact_ivp(act, xt, lam, 0, contact_fd)) {
        xt[j] = x[j] - kForwardStep * std::max(std::abs(x[j]), typ[j]);
        h = xt[j] - x[j];
        if (!contact_ivp(act, xt, lam, 0, contact_fd)) {
          why = "the IVP failed while differencing the contact Jacobian (both sides)";
          return Summary::Status::kLineSearchFailed;
        }
      }
      stack_residual(contact_fd.r, contact_fd.gap, active, L, Ft);
      J.col(j) = (Ft - F) / h;
    }
    contact_fd = contact_iv;  // the states before each node
    for (int a = 0; a < na; ++a) {
      const int pair = active[static_cast<std::size_t>(a)];
      lam_t = lam;
      const double h0 = kForwardStep * std::max(std::abs(lam[pair]), Fc);
      lam_t[pair] = lam[pair] + h0;
      double h = lam_t[pair] - lam[pair];
      const int node = pair / g.per_node() + 1;
      if (!contact_ivp(act, x, lam_t, node, contact_fd)) {
        lam_t[pair] = lam[pair] - h0;
        h = lam_t[pair] - lam[pair];
        if (!contact_ivp(act, x, lam_t, node, contact_fd)) {
          why = "the IVP failed while differencing the contact Jacobian (both sides)";
          return Summary::Status::kLineSearchFailed;
        }
      }
      stack_residual(contact_fd.r, contact_fd.gap, active, L, Ft);
      J.col(nx + a) = (Ft - F) / h;
      // Restore the nodes after `node` for the next column (the gaps and states before the
      // next column's node are those of contact_iv again).
      for (std::size_t k = static_cast<std::size_t>(node) + 1; k < contact_iv.y_node.size(); ++k)
        contact_fd.y_node[k] = contact_iv.y_node[k];
      for (int i = node * g.per_node(); i < n_pairs; ++i) contact_fd.gap[i] = contact_iv.gap[i];
    }
    dz = J.partialPivLu().solve(-F);
    if (!dz.allFinite()) {
      why = "singular contact Jacobian";
      return Summary::Status::kSingularJacobian;
    }
    const double phi = 0.5 * F.squaredNorm();
    double t = 1.0;
    bool accepted = false;
    for (int ls = 0; ls < options.max_line_search_steps; ++ls, t *= 0.5) {
      xt = x + t * dz.head(nx);
      lam_t = lam;
      for (int a = 0; a < na; ++a) lam_t[active[a]] += t * dz[nx + a];
      if (contact_ivp(act, xt, lam_t, 0, contact_trial) && !tunnels(contact_trial, in)) {
        stack_residual(contact_trial.r, contact_trial.gap, active, L, Ft);
        if (0.5 * Ft.squaredNorm() <= (1.0 - 2.0 * kArmijo * t) * phi) {
          accepted = true;
          break;
        }
      }
    }
    if (!accepted) {
      why = "line search found no decrease of the contact residual along the Newton direction";
      return Summary::Status::kLineSearchFailed;
    }
    ++summary.iterations;
    x = xt;
    lam = lam_t;
    std::swap(contact_iv, contact_trial);
    // The set changes only once the iteration on it has (nearly) converged: the signs and
    // gaps of a half-converged step are not reliable (a pair released on them comes back at
    // once, and the set cycles). Only deep penetrations enter at once (a node must not pass
    // through a thin obstacle), except those released at the last update until the set has
    // converged again.
    std::vector<char> next = in;
    ++on_this_set;
    const bool settled =
        Ft.lpNorm<Eigen::Infinity>() <= kSettledResidual || on_this_set >= kMaxStepsPerSet;
    update_active(in, lam, contact_iv, cautious, settled, next);
    if (settled) {
      for (int i = 0; i < n_pairs; ++i) recent[i] = in[i] && !next[i];
    } else {
      for (int i = 0; i < n_pairs; ++i) {
        if (recent[i]) next[i] = in[i];
      }
    }
    changed = next != in;
    if (changed) on_this_set = 0;
    if (changed) {
      if (!cautious && std::find(seen.begin(), seen.end(), next) != seen.end()) cautious = true;
      seen.push_back(in);
      bool released = false;
      for (int i = 0; i < n_pairs; ++i) {
        if (!next[i] && lam[i] != 0.0) {
          lam[i] = 0.0;
          released = true;
        }
      }
      in = next;
      if (released && !contact_ivp(act, x, lam, 0, contact_iv)) {
        why = "the IVP with contact forces failed after releasing contact points";
        return Summary::Status::kLineSearchFailed;
      }
    }
  }
}

bool ShootingSolver::Impl::free_solve(const rod::Loads& act, Solution& sol, Summary& out) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!free_solver) {
    free_model = std::make_unique<rod::RodModel>(model);
    free_model->obstacles.clear();
    free_solver = std::make_unique<ShootingSolver>(*free_model, free_options);
  }
  Solution fs = sol;  // its warm-start fields are the last free solution's (or cleared)
  fs.contact_lambda_N.clear();
  Summary s = free_solver->solve(act, fs);
  if (!s.converged() || fs.unknowns.size() != nx) return false;
  const ContactGrid& g = contact_grid;
  const std::vector<double> open(static_cast<std::size_t>(g.pairs()), 0.0);
  contact_fraction = 1.0;
  if (!contact_ivp(act, fs.unknowns, open, 0, contact_iv)) return false;
  for (const rod::SectionGap& gap : contact_iv.gap) {
    if (gap.gap_m < -options.tolerance * L) return false;
  }
  // Clear is not enough: the free rod may have passed through an obstacle (a node beyond a
  // sphere is clear again). From where the solve starts (the warm start's unknowns under
  // these loads, as the contact iteration's first iterate; cold: the unloaded rod) no node
  // may move farther than its clearance there plus the obstacle's half thickness.
  const bool warm = sol.valid && sol.unknowns.size() == nx && sol.unknowns.allFinite();
  contact_fraction = warm ? 1.0 : 0.0;
  const bool started = contact_ivp(act, warm ? sol.unknowns : initial_guess(act, 0.0, false), open,
                                   0, contact_trial);
  contact_fraction = 1.0;
  if (!started) return false;
  const int n_nodes = static_cast<int>(g.s.size()) - 1;
  for (int k = 1; k <= n_nodes; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const double moved =
        (contact_iv.y_node[ku].segment<3>(kP) - contact_trial.y_node[ku].segment<3>(kP)).norm();
    for (int col = 0; col < g.per_node(); ++col) {
      const double clear = std::max(
          0.0, contact_trial.gap[static_cast<std::size_t>((k - 1) * g.per_node() + col)].gap_m);
      if (moved >
          clear + half_thickness_m(model.obstacles[static_cast<std::size_t>(col / g.n_cand)])) {
        return false;
      }
    }
  }
  fs.contact_lambda_N = open;
  sol = std::move(fs);
  // No memo and no recorded samples belong to this solver's IVPs (make_result integrates).
  memo_valid = false;
  acc_samples.valid = false;
  acc_full_load = false;
  out = s;
  out.ivp_count += 1;
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

Summary ShootingSolver::Impl::contact_solve(const rod::Loads& act, Solution& sol) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n_pairs = contact_grid.pairs();
  const bool warm = sol.valid && sol.unknowns.size() == nx && sol.unknowns.allFinite() &&
                    static_cast<int>(sol.contact_lambda_N.size()) == n_pairs;
  const bool start_open =
      !warm || std::all_of(sol.contact_lambda_N.begin(), sol.contact_lambda_N.end(),
                           [](double l) { return l == 0.0; });
  {
    Summary free;
    if (start_open && free_solve(act, sol, free)) return free;
  }
  Summary summary;
  std::string why;
  Eigen::VectorXd x;
  std::vector<double> lam;
  Summary::Status st = Summary::Status::kNotRun;
  int ivps = 0;
  if (warm) {
    ivp_count = 0;
    x = sol.unknowns;
    lam = sol.contact_lambda_N;
    st = active_set_newton(act, x, lam, summary, why);
    ivps = ivp_count;
  }
  if (st != Summary::Status::kConverged) {
    // Cold (or a failed warm start): continuation in the load fraction from the unloaded
    // rod (the reference shape, clear of the obstacles), the full load first; a failed step
    // is halved, a successful one doubles the next. A step that moves a node farther than
    // kMaxStepMotion L is halved too: with obstacles a rod has several equilibria (held on
    // one side of an obstacle or slid past it; draped on a floor or curled up above it), and
    // the one reached by ramping the loads quasi-statically is the one a user means. Large
    // steps jump to others (a soft rod on a floor reached a looped shape standing on its tip
    // in one step).
    std::string cold_why;
    Eigen::VectorXd xc = initial_guess(act, 0.0, false);
    std::vector<double> lc(static_cast<std::size_t>(n_pairs), 0.0);
    contact_fraction = 0.0;
    ivp_count = 0;
    st = active_set_newton(act, xc, lc, summary, cold_why);
    std::vector<Vec3> nodes_c;  // the node positions of the last accepted step
    auto node_positions = [&](std::vector<Vec3>& out) {
      out.clear();
      for (const Eigen::VectorXd& yk : contact_iv.y_node) out.push_back(yk.segment<3>(kP));
    };
    node_positions(nodes_c);
    std::vector<Vec3> nodes_t;
    double done = 0.0, step = 1.0;
    while (st == Summary::Status::kConverged && done < 1.0) {
      Eigen::VectorXd xt = xc;
      std::vector<double> lt = lc;
      contact_fraction = std::min(1.0, done + step);
      const Summary::Status s_step = active_set_newton(act, xt, lt, summary, cold_why);
      if (s_step == Summary::Status::kConverged) {
        node_positions(nodes_t);
        double moved = 0.0;
        for (std::size_t k = 0; k < nodes_t.size() && k < nodes_c.size(); ++k)
          moved = std::max(moved, (nodes_t[k] - nodes_c[k]).norm());
        // (Down to 4 x the smallest step: a genuine snap of the path is taken.)
        if (moved > kMaxStepMotion * L && step > 4.0 * options.min_continuation_step) {
          step *= 0.5;
          continue;
        }
        nodes_c.swap(nodes_t);
        done = contact_fraction;
        xc = xt;
        lc = lt;
        if (done < 1.0) ++summary.continuation_steps;
        step = std::min(2.0 * step, 1.0 - done);
      } else {
        x = xt;  // the last iterate, when this was the last chance
        lam = lt;
        st = s_step;
        step *= 0.5;
        if (step < options.min_continuation_step) {
          cold_why = "contact continuation stalled at load fraction " + format_value(done) + ": " +
                     cold_why;
          break;
        }
        st = Summary::Status::kConverged;
      }
    }
    contact_fraction = 1.0;
    if (st == Summary::Status::kConverged) {
      x = xc;
      lam = lc;
    }
    ivps += ivp_count;
    why = warm ? "from the warm start: " + why + "; from the unloaded rod: " + cold_why : cold_why;
  }
  // No memo and no recorded samples belong to a contact solution (they are plain IVPs').
  memo_valid = false;
  acc_samples.valid = false;
  acc_full_load = false;
  summary.status = st;
  summary.message = st == Summary::Status::kConverged ? std::string() : why;
  summary.characteristic_force_N = rod::characteristic_force_N(model, act);
  summary.equilibrium_residual.reset();
  sol.unknowns = x;
  sol.contact_lambda_N = lam;
  sol.jacobian.resize(0, 0);
  sol.coarse_unknowns.resize(0);
  sol.coarse_jacobian.resize(0, 0);
  sol.path.clear();
  sol.tensions_N.assign(n_act, 0.0);
  sol.elongations_m.assign(n_act, 0.0);
  sol.tip_state.resize(0);
  if (contact_ivp(act, x, lam, 0, contact_iv)) {
    sol.tip_state = y;
    summary.equilibrium_residual =
        equilibrium_residual(contact_iv.r, summary.characteristic_force_N);
    for (int i = 0; i < n_act; ++i) {
      sol.tensions_N[i] = cT[i] / count[i];
      sol.elongations_m[i] = y[delta_offset + i];
    }
    // Global equilibrium with the contact forces among the applied loads.
    equilibrium(act, x, y, summary);
    for (const rod::ContactResult& c : contact_results(lam, contact_iv)) {
      summary.force_imbalance_W_N -= c.force_W_N;
      summary.moment_imbalance_W_Nm -= c.moment_W_Nm;
    }
  }
  sol.valid = st == Summary::Status::kConverged;
  summary.ivp_count = ivps + 1;
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

std::vector<rod::ContactResult> ShootingSolver::Impl::contact_results(
    const std::vector<double>& lam, const ContactIvp& iv) const {
  const ContactGrid& g = contact_grid;
  std::vector<rod::ContactResult> out;
  const int n = static_cast<int>(g.s.size()) - 1;
  for (int o = 0; o < g.n_obs; ++o) {
    std::vector<rod::ContactSample> node_samples;
    node_samples.reserve(static_cast<std::size_t>(n * g.n_cand));
    for (int k = 1; k <= n; ++k) {
      for (int j = 0; j < g.n_cand; ++j) {
        const auto pair = static_cast<std::size_t>((k - 1) * g.per_node() + o * g.n_cand + j);
        const rod::SectionGap& sg = iv.gap[pair];
        if (!std::isfinite(sg.gap_m) && lam[pair] == 0.0) continue;
        rod::ContactSample c;
        c.s_m = g.s[static_cast<std::size_t>(k)];
        c.point_W_m = iv.y_node[static_cast<std::size_t>(k)].segment<3>(kP) + sg.offset_W_m;
        c.force_W_N = lam[pair] * sg.normal_W;
        c.gap_m = sg.gap_m;
        node_samples.push_back(c);
      }
    }
    out.push_back(rod::summarize_contact(model.obstacles[static_cast<std::size_t>(o)], node_samples,
                                         model.base_position_W_m));
  }
  return out;
}

}  // namespace tcasim::cosserat
