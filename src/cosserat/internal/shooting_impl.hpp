#pragma once
/// The shooting solver's state behind ShootingSolver (cosserat/shooting.hpp): the layers
/// RodProblem (constant layout, problem.hpp) <- RodRhs (IVP right-hand sides, rhs.hpp) <-
/// TipConditions (residual rows, tip_conditions.hpp) on one Layout (layout.hpp: 3-D,
/// layout_3d.cpp, or the planar reduction, planar_layout.cpp), plus the IVP levels and what
/// the solver stages keep between calls. The stages are defined in one file each:
///   shooting.cpp          driver: construction, solve(), results
///   shooting_map.cpp      r(x) and dr/dx by one IVP on the active level, the IVP memo
///   newton.cpp            damped Newton, line search, Broyden updates, FD Jacobians,
///                         continuation in the load fraction
///   warm_start.cpp        the multi-level start (coarse, middle/Richardson, coarse-grid
///                         correction), the path extrapolation of sweeps, TCA row refresh
///   initial_guess.cpp     the closed-form cold-start guess with gravity
///   contact.cpp           obstacles: the contact grid, the IVP with the contact point
///                         forces, the active-set Newton iteration, contact results
/// Internal to the shooting solver.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosserat/internal/integration_level.hpp"
#include "cosserat/internal/tip_conditions.hpp"
#include "cosserat/shooting.hpp"
#include "rod/obstacle.hpp"

namespace tcasim::cosserat {

/// The names the stage files above use unqualified (`using namespace stage_names;`).
namespace stage_names {
using namespace state_layout;
using internal::all_finite;
using internal::Mat3;
using internal::Vec3;
using internal::Vec6;
}  // namespace stage_names

struct ShootingSolver::Impl : internal::TipConditions {
  using Vec3 = internal::Vec3;
  using Mat3 = internal::Mat3;
  using Vec6 = internal::Vec6;
  using IntegrationLevel = internal::IntegrationLevel;

  /// layout: 3-D (internal::make_3d_layout) or the planar reduction.
  Impl(const rod::RodModel& m, const Options& o, std::unique_ptr<internal::Layout> layout);

  // --- driver (shooting.cpp)
  static Options validated(const rod::RodModel& m, Options o);
  /// Options::jacobian = kForwardDifference when nx > kMaxSensitivityUnknowns.
  static Options with_jacobian_fallback(Options o, int nx);
  /// ShootingSolver::solve in this Impl's layout: sol's unknowns and tip state are 3-D on
  /// entry and on return (the Jacobians, the coarse-level fields and the path stay in the
  /// layout's unknowns); the global equilibrium is checked on the 3-D solution.
  Summary solve(const rod::Loads& act, Solution& sol);
  /// solve() with sol's unknowns and tip state in the layout's.
  Summary solve_in_layout(const rod::Loads& act, Solution& sol);
  /// Sets sol's unknowns, tensions, elongations and tip state at x (full load), and leaves
  /// the IVP parameters set for x at full load.
  /// Summary::equilibrium_residual of the scaled residual r at full load, with F_c of the
  /// solve's loads (rod::characteristic_force_N, computed once per solve by finish()).
  double equilibrium_residual(const Eigen::VectorXd& r, double characteristic_force_N) const;
  void finish(const rod::Loads& act, const Eigen::VectorXd& x, Solution& sol, Summary& summary);
  rod::Result make_result(const rod::Loads& act, const Solution& sol, const Summary& summary);
  /// What the clamp applies to the rod (rod::Result::base_reaction) for the 3-D unknowns x
  /// with the actuator tensions of res: minus the total section wrench at s = 0 (the rod's
  /// n(0), m(0) and the strings leaving the base; moment about the base point).
  rod::Wrench base_reaction(const Eigen::VectorXd& x, const rod::Result& res) const;
  /// Fills res.probes after make_result's sampling pass: a probe at a sample from it, any other
  /// from the sample before its s integrated on to s (output_level->integrate_between).
  /// False when such an integration fails.
  bool probe_results(rod::Result& res, const std::vector<Eigen::VectorXd>& sample_states);

  // --- the shooting map r(x) (shooting_map.cpp)
  /// Scaled residual at x; y(L) left in `y`. False when the IVP or a TCA law fails.
  bool residual(const rod::Loads& act, double lambda, const Eigen::VectorXd& x, Eigen::VectorXd& r);
  /// Residual and its exact Jacobian from one augmented IVP (kSensitivity).
  bool residual_and_jacobian(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                             Eigen::VectorXd& r, Eigen::MatrixXd& J);
  /// Whether the memo holds y(L) of the IVP from x with the parameters last set
  /// (set_parameters) on level `on` (the active level unless given).
  bool memo_answers(const Eigen::VectorXd& x, const IntegrationLevel* on = nullptr) const;
  /// Records x (at load fraction lambda, the active level) as the accepted point of the IVP
  /// memo: y(L), the IVP parameters and the contact derivatives there.
  void remember(double lambda, const Eigen::VectorXd& x);

  // --- Newton iteration (newton.cpp)
  /// Damped Newton at load fraction lambda: the Jacobian (sensitivities or differences) is
  /// computed at x when missing; after an accepted step it is Broyden-updated (trial points
  /// cost one plain IVP) unless the step reduced ||r|| by less than kBroydenMinReduction
  /// (then it is recomputed at the new point); a stale Jacobian gets kStaleLineSearchSteps
  /// halvings before it is recomputed. x and J are in/out (J.size() == 0: no Jacobian yet).
  Summary::Status newton(const rod::Loads& act, double lambda, Eigen::VectorXd& x,
                         Eigen::MatrixXd& J, Summary& summary, std::string& why, double tolerance);
  /// Sensitivity Jacobian for Newton at x (r: the residual at x, kept). On the fine level
  /// with a coarse level (Options::coarse_steps), the first request at a point uses the coarse
  /// level's sensitivities (coarse_steps / steps of the cost; within the coarse discretization
  /// error of the fine Jacobian) and sets `approximate`; a second request at the same point
  /// (the approximate one failed) computes the fine Jacobian.
  bool newton_jacobian(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                       Eigen::VectorXd& r, Eigen::MatrixXd& J, bool& approximate);
  /// Forward or central differences of the residual (Options::jacobian), r0 = r(x).
  bool fd_jacobian(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                   const Eigen::VectorXd& r0, Eigen::MatrixXd& J);
  /// Typical sizes of the unknowns (floor of the finite-difference steps).
  Eigen::VectorXd typical_scale() const;
  /// Continuation in the load fraction lambda from 0 to 1 after a failed direct solve (why:
  /// its reason on entry, the outcome's on return), warm-starting each step on the fine
  /// level; on return x, J are the last accepted point and its Jacobian (empty on failure).
  Summary::Status continuation(const rod::Loads& act, Eigen::VectorXd& x, Eigen::MatrixXd& J,
                               Summary& summary, std::string& why);

  // --- warm starts and the multi-level start (warm_start.cpp)
  /// Direct solve at full load from x (warm: the previous solution, J its Jacobian; cold: the
  /// guess, J empty or a warm start's Jacobian for the coarse level) with the two-level start
  /// (Options::coarse_steps); on return x and J are the last accepted point and its Jacobian, and
  /// sol's coarse fields are set.
  Summary::Status direct_solve(const rod::Loads& act, Solution& sol, bool warm, Eigen::VectorXd& x,
                               Eigen::MatrixXd& J, Summary& summary, std::string& why);
  /// The cost check of a warm start that would go straight to the fine level (a coarse level,
  /// a Jacobian J, Options::warm_start_fine_only), decided on the coarse level before any fine
  /// IVP. The cold path's fine level starts at the Richardson extrapolation of the coarse and
  /// middle solutions (within their discretization error of the fine solution, one or two
  /// fine IVPs from convergence), while the fine Newton iteration from a warm point costs one
  /// fine IVP per step. So a warm point whose scaled coarse residual exceeds sqrt(tolerance)
  /// (more than one Newton step from convergence) is used only if its Newton step J^-1 r to
  /// the coarse solution (each unknown relative to its size) is not longer than the cold
  /// guess's. A warm point whose fine IVP the memo answers (only temperatures or tip loads
  /// changed: the fine residual is free, the refreshed Jacobian near exact) is always used.
  /// Returns false (with x_cold the guess, loaded_guess as initial_guess sets it, and the
  /// memo at the guess on the coarse level) when the cold path should run; costs one coarse
  /// IVP, or two and the guess when the warm point is that far.
  bool warm_start_pays(const rod::Loads& act, const Solution& sol, const Eigen::MatrixXd& J,
                       Eigen::VectorXd& x_cold, bool& loaded_guess);
  /// Cold start: converges the middle level (2 N_c steps) from the coarse solution xc and
  /// starts the fine level (N_f steps) at the Richardson extrapolation of the two, which
  /// removes the leading O(h^p) term (p: the method's order, 4, 6 or 8) of the discretization
  /// error of x:
  ///   x(N) = x* + C N^-p  =>  x(N_f) = x_m + (x_m - x_c) (N_f^-p - N_m^-p) / (N_m^-p - N_c^-p).
  /// On failure x, J keep the coarse solution.
  void cold_extrapolation(const rod::Loads& act, const Eigen::VectorXd& xc,
                          const Eigen::MatrixXd& Jc, Eigen::VectorXd& x, Eigen::MatrixXd& J,
                          Summary& summary);
  /// Warm start: the actuation change (temperatures) alters the TCA rows of the Jacobian
  /// only through the contact residual's derivatives (the IVP does not depend on
  /// temperatures). Row k is (a e_k + b ddelta/dx) / F_c with a = dphi/dT_k, b = dphi/d delta,
  /// so it is rebuilt from the previous solution's (a, b) and the new ones at the same point
  /// under `act` (the residual there comes from the IVP memo, without integration).
  void refresh_tca_rows(const rod::Loads& act, const Eigen::VectorXd& x, Eigen::MatrixXd& J);
  /// Cold start of a body whose reference curvature varies along s under a distributed load
  /// (the guess, a constant-strain arc, knows neither the variation nor, for a heavy soft
  /// body, the weight): a homotopy in omega*'s variation (RodProblem::set_omega_star_fraction).
  /// The body with the base's omega* throughout (mu = 0) is solved from the guess as a cold
  /// start is (direct_solve, and from the guess without gravity if that fails); then mu steps
  /// to 1 by warm direct solves, straight to 1 first, the step halved after a failure (down to
  /// Options::min_continuation_step). Returns kConverged with x, J, sol's coarse fields at the
  /// model (mu = 1); otherwise the status of the failed stage (the caller then runs the
  /// ordinary cold start) with mu back at 1.
  Summary::Status omega_star_homotopy(const rod::Loads& act, Solution& sol, Eigen::VectorXd& x,
                                      Eigen::MatrixXd& J, Summary& summary, std::string& why);
  /// The actuation as a flat vector (documented at ShootingSolver::solve).
  static Eigen::VectorXd actuation_vector(const rod::Loads& act);
  /// Extrapolates the unknowns to the actuation a along Solution::path: the newest points
  /// whose actuations lie on the line through the last one and a, with parameter t (0 at
  /// the last point, 1 at a), each older point at least kPathMinSpacing behind the next (no
  /// wild extrapolation from clustered points), are interpolated by the Lagrange polynomial
  /// in t evaluated at t = 1. Returns false when fewer than two points qualify (or a is the
  /// last point's actuation).
  static bool extrapolate_path(const Solution& sol, const Eigen::VectorXd& a, int nx,
                               Eigen::VectorXd& x);
  /// Updates Solution::path after a solve (see its documentation).
  static void record_path(Solution& sol, bool warm, bool converged, Eigen::VectorXd a);

  // --- initial guess (initial_guess.cpp)
  /// Initial guess (docs/conventions.md "Initial guess"): the closed-form constant-strain rod
  /// of the known tensions and of the TCA tensions solving T_k = F_tca(delta_k(T)) with the
  /// closed-form elongations (a small Newton iteration; T_tca = 0 if it fails), plus, if
  /// `with_gravity`, the strains of gravity on that bent rod: a fixed-point iteration bends
  /// the arc by their mean and the unknowns take their value at the base. Without a converged
  /// fixed point gravity is ignored; *used_gravity tells whether it was included. Tip loads
  /// are ignored (large ones, e.g. a holder's reaction, admit other equilibria). Computed in
  /// the 3-D unknowns and returned in the layout's (Layout::reduce_unknowns).
  Eigen::VectorXd initial_guess(const rod::Loads& act, double lambda, bool with_gravity,
                                bool* used_gravity = nullptr);
  /// TCA tensions of the guess (rod::solve_guess_tensions): T_k = F_tca(delta_k(T)) with
  /// delta_k of the closed-form strains plus `extra` (the mean load strains); sets the TCA
  /// entries of the 3-D unknowns x (0 if it fails) and their c T in cTs (known tensions as
  /// set by set_parameters).
  void guess_tensions(const Vec6& extra, std::vector<double>& cTs, Eigen::VectorXd& x);
  /// Pose at arc length s of a rod with constant strains (nu, omega) from the base pose:
  /// R = R0 exp(s hat(omega)), p = p0 + R0 V nu with V = int_0^s exp(t hat(omega)) dt.
  void arc_pose(const Vec3& nu, const Vec3& omega, double s, Mat3& R, Vec3& p) const;
  /// Strains the distributed load f_ext_W (gravity) adds to a rod bent with constant strains
  /// (nu, omega): K^-1 R(s)^T times the internal force and moment the load beyond s requires
  /// (docs/conventions.md "Global equilibrium"), on kGuessNodes + 1 nodes; returns their mean
  /// over s and their value at s = 0.
  void load_strains(const Vec3& nu, const Vec3& omega, Vec6& mean, Vec6& base) const;

  // --- contact with obstacles (contact.cpp; docs/conventions.md "Contact in the shooting
  // method")
  /// The contact points: the step nodes s_k (k = 1..n) of the fine level's grid (pieces
  /// included), each against each model obstacle with each contact candidate of the section
  /// (rod::section_gaps: 1 for a circle, 8 for a rectangle); pair index
  /// ((k - 1) n_obs + o) n_cand + j.
  struct ContactGrid {
    std::vector<double> s;                     ///< nodes s_0 = 0 < ... < s_n = L
    std::vector<int> piece;                    ///< per step k -> k + 1: its piece (or 0)
    std::vector<int> knot;                     ///< per node: the interior knot there, or -1
    std::vector<rod::ContactOutline> outline;  ///< per node
    int n_obs = 0;
    int n_cand = 1;  ///< candidates per section (the most any node's outline has)
    int per_node() const { return n_obs * n_cand; }
    int pairs() const { return (static_cast<int>(s.size()) - 1) * per_node(); }
  };
  /// One IVP with contact forces: the state at each node before its contact jump (and its
  /// knot jump), the gaps of all pairs, y(L) and the tip residual.
  struct ContactIvp {
    std::vector<Eigen::VectorXd> y_node;
    std::vector<rod::SectionGap> gap;
    Eigen::VectorXd r;
  };
  void build_contact_grid();
  /// Integrates the IVP of unknowns x with the contact forces lam[pair] n at the touching
  /// points from node `from` to L: from 0 it starts at y(0), else at iv.y_node[from] (the
  /// nodes and gaps before `from` are kept). At node k the state jumps by the point forces
  /// of its pairs (RodRhs::point_wrench_jump), then by a knot's strain jump. observer (if
  /// given) sees every node after its jumps. Sets iv.r (the tip residual) and leaves y(L)
  /// in `y`. False when the IVP, a jump or a TCA law fails.
  bool contact_ivp(const rod::Loads& act, const Eigen::VectorXd& x, const std::vector<double>& lam,
                   int from, ContactIvp& iv, const ode::Observer* observer = nullptr);
  /// The solve with obstacles: a warm start from sol's unknowns and multipliers; else (or if
  /// that fails) a continuation in the load fraction from the unloaded rod, the full load
  /// first, halving failed steps and doubling after successes.
  Summary contact_solve(const rod::Loads& act, Solution& sol);
  /// Primal-dual active-set Newton iteration on z = (x, lam of the active pairs); x, lam
  /// in/out (the last iterate).
  Summary::Status active_set_newton(const rod::Loads& act, Eigen::VectorXd& x,
                                    std::vector<double>& lam, Summary& summary, std::string& why);
  /// What the obstacles do in the solution (x, lam): one ContactResult per obstacle.
  std::vector<rod::ContactResult> contact_results(const std::vector<double>& lam,
                                                  const ContactIvp& iv) const;
  /// With no contact in the start (a cold solve, or a warm one whose multipliers are all
  /// zero): the free rod by the plain solver of the model without obstacles (planar reduction,
  /// coarse levels, sensitivity Jacobians), which stands if no pair of the contact grid
  /// penetrates it (gap >= -tolerance L). True with sol and out set; false (sol untouched)
  /// when it does not converge or touches.
  bool free_solve(const rod::Loads& act, Solution& sol, Summary& out);
  Options free_options;                       // the options as given (coarse levels on)
  std::unique_ptr<rod::RodModel> free_model;  // the model without its obstacles (lazily)
  std::unique_ptr<ShootingSolver> free_solver;
  ContactGrid contact_grid;
  double contact_fraction = 1.0;  // load fraction of contact_ivp (cold-start continuation)
  std::optional<ode::Integrator> contact_step;  // one step of the fine level's method
  ContactIvp contact_iv, contact_trial, contact_fd;
  std::vector<rod::SectionGap> candidates;  // section_gaps of one node and obstacle

  Options options;
  // IVP levels: the fine one (Options::integrator), the coarse one (Options::coarse_steps)
  // and, for cold starts, a middle one with 2 x coarse_steps (when 4 x coarse_steps <=
  // steps): the fine start is the Richardson extrapolation of the coarse and middle
  // solutions. `level` is the active one; output_level samples results (make_result).
  IntegrationLevel fine_level;
  std::optional<IntegrationLevel> coarse_level, mid_level, output_level;
  IntegrationLevel* level = nullptr;
  Eigen::VectorXd y;  // y(L) of the last IVP
  Eigen::VectorXd Y;  // augmented state (sensitivities)

  Eigen::VectorXd y_acc, x_acc;  // y(L) at the last accepted point x_acc (load fraction 1 only)
  bool acc_full_load = false;
  // IVP memo across solves: y(L) = y_acc is reused when the next IVP has the same initial
  // unknowns, IVP parameters (cT, f_ext) and level, e.g. the first residual of a warm start
  // whose actuation changed only temperatures or tip loads (they enter the tip residual only).
  bool memo_valid = false;
  std::vector<double> acc_cT;
  std::vector<double> acc_dphi_dT, acc_dphi_ddelta;  // at the accepted point (its actuation)
  Vec3 acc_f_ext = Vec3::Zero();
  const IntegrationLevel* acc_level = nullptr;
  double acc_omega_star_fraction = 1.0;
  // Samples of the plain fine-level IVPs (s and the layout's state at every step node, the
  // nodes make_result samples), when record_samples is set (fixed-step flat integration,
  // Options::centerline_intervals = 0). `samples` are valid when the last IVP was such an
  // IVP: they belong to y as remember() takes it (the last IVP, from the point it is given);
  // remember() keeps them as the accepted point's, beside y_acc. make_result replays those
  // when the memo holds its solution instead of integrating it again: the same IVP with the
  // same observer, so the same numbers.
  struct Samples {
    std::vector<double> s, y;  // y: dim values per node
    bool valid = false;
  };
  bool record_samples = false;
  ode::Observer sample_recorder;  // appends to `samples`
  Samples samples, acc_samples;
  Eigen::VectorXd coarse_jacobian_x;  // where the last coarse-level Newton Jacobian was taken
  int jacobian_updates = 0;  // Broyden updates of newton()'s Jacobian since it was computed
  int ivp_count = 0;
};

}  // namespace tcasim::cosserat
