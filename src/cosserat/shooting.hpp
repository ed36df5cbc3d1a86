#pragma once
/// Forward kinetostatics of a Cosserat rod with string actuators by shooting
/// ([Pawlowski2019] Section III, with the corrected equations of docs/conventions.md).
///
/// IVP state (dimension 21 + n_actuators), all in SI:
///   y = ( p_W [0,3), R_WB [3,12) column-major (y[3 + 3 j + i] = R(i, j)),
///         e_B = nu_B - nu* [12,15) (nu* = e3), omega_B [15,18), c_W = int_0^s p_W ds
///         [18,21) (for the global equilibrium check), delta_i [21, 21 + n_actuators) ).
/// Unknowns x = ( e_B(0) = nu_B(0) - nu* 3, omega_B(0) 3, T_i for each TCA-driven actuator
/// in model order, tip-constraint reaction ); tension-driven actuators have known tensions.
/// Why the deviation e and not nu (docs/conventions.md "Shooting states and unknowns"): the
/// internal force n_B = K_nu e is then computed from a number that carries its own digits,
/// whereas K_nu (nu - nu*) from nu ~ 1 has an absolute error eps K_nu, i.e. a relative error
/// eps EA L^2 / EI of the force scale EI / L^2: 1e-4 for EA L^2 / EI = 1e12. The deviation
/// changes nothing else: its derivative, sensitivities and the discretization are those of nu.
/// Tip constraint (RodModel::tip_constraint): pinned adds the reaction force lambda_W (3,
/// world frame, the force the holder applies to the rod) and the residual
/// (p(L) - p_target) / L (3); normal-only adds lambda (1; reaction lambda n) and
/// n . (p(L) - p_target) / L (1). The reaction is added to F_e in the tip conditions, is
/// not scaled by the continuation's load fraction, and is reported as
/// rod::Result::tip_reaction_force_W_N.
/// Residual r(x) (docs/conventions.md "Tip conditions"), scaled:
///   r[0:3] = ( K_nu (nu(L) - nu*) - R^T F_e + sum c_i T_i qh_i ) / F_c
///   r[3:6] = ( K_omega (omega(L) - omega*) - R^T M_e + sum c_i T_i r_i x qh_i ) / (F_c L)
///   r[6+k] = phi_k( T_k, delta_k(L) ) / F_c, phi_k = T_k - F_tca(delta_k(L), temperatures_k)
///            with coil contact (tca::contact_residual; docs/conventions.md "Closed coils")
/// with the characteristic force F_c = max(min(E I_x, E I_y) / L^2, the model's own largest
/// load: |F_e|, |M_e| / L, the weight rho A |g| L, c_i |T_i| of tension drives;
/// rod::characteristic_force_N of the model's own loads), fixed when the solver is built.
/// Summaries also report the residual both methods share (Summary::equilibrium_residual). The force
/// residual is K_nu e to the relative precision of e, so the scale needs no stiffness floor; its
/// round-off is eps times the largest load it sums. Convergence: ||r||_inf <= Options::tolerance.
/// Non-convergence is a Summary status, never an exception; a non-finite IVP or a TCA law
/// DomainError at a trial point is a failed trial (the line search backs off).
/// Planar problems are solved in the plane with the in-plane states and unknowns
/// (Options::planar_reduction, cosserat/planar.cpp); Solution::unknowns and tip_state keep
/// the layouts above.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/ode.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"
#include "tca/tca.hpp"

namespace tcasim::cosserat {

/// Offsets of the IVP state blocks (layout documented above).
namespace state_layout {
inline constexpr int kP = 0;       ///< p_W, 3
inline constexpr int kR = 3;       ///< R_WB column-major, 9
inline constexpr int kNu = 12;     ///< nu_B, 3
inline constexpr int kOmega = 15;  ///< omega_B, 3
inline constexpr int kC = 18;      ///< int_0^s p_W ds, 3
inline constexpr int kDelta = 21;  ///< delta_i, one per actuator
}  // namespace state_layout

/// How the shooting Jacobian dr/dx is obtained.
enum class JacobianMethod {
  /// Forward sensitivities dy/dx integrated with the state (variational equations, one
  /// augmented IVP of dimension dim (1 + nx)): the exact derivative of the discrete
  /// (RK4) residual map; to the integration tolerance with CVODE. Models with more than
  /// 10 TCA drives fall back to kForwardDifference.
  kSensitivity,
  /// Forward differences, step h_j = sqrt(eps) max(|x_j|, typical_j): error O(h_j),
  /// about 1e-8 relative (one IVP per unknown).
  kForwardDifference,
  /// Central differences, step h_j = eps^(1/3) max(|x_j|, typical_j): error O(h_j^2),
  /// about 1e-10 relative (two IVPs per unknown).
  kCentralDifference,
};

/// How the shooting IVP advances the pose (p_W, R_WB); the other state components (strains,
/// c, delta) and the sensitivities always use the same stages as the pose.
enum class Kinematics {
  /// The flattened state (p, R column-major, ...) by Options::integrator (RK4 or CVODE).
  kFlat,
  /// Fourth-order Runge-Kutta-Munthe-Kaas steps on SE(3) (cosserat/lie_rkmk4.cpp) with
  /// `integrator.steps` equal steps (needs integrator.method = kRk4): exact for constant
  /// strains at any step count, order 4 otherwise, R orthogonal to round-off.
  kLieGroup,
};

/// Solver options (validated by ShootingSolver's constructor: InputError naming the field).
struct Options {
  /// IVP integrator: kRk4 (the paper's scheme), kRk6 or kRk8 with `steps` (even, so a node
  /// lies at L/2), or kCvode with `relative_tolerance`. output_intervals is ignored (set by
  /// the solver).
  ode::IntegratorOptions integrator;
  /// Pose integration: kFlat (default) or the Lie-group RKMK4 method.
  Kinematics kinematics = Kinematics::kFlat;
  /// Converged when the scaled residual satisfies ||r||_inf <= tolerance.
  double tolerance = 1e-10;
  int max_iterations = 50;         ///< Newton iterations per solve (per continuation step)
  int max_line_search_steps = 12;  ///< backtracking halvings per Newton iteration (t >= 2^-11)
  JacobianMethod jacobian = JacobianMethod::kSensitivity;
  /// Finite-difference Jacobians only: after the first one, update it with Broyden's rank-one
  /// formula on accepted steps; a stalled line search recomputes it by differences.
  bool broyden_updates = true;
  /// Retry a failed solve by continuation in the actuation (see ShootingSolver::solve).
  bool continuation = true;
  /// Smallest continuation step in the load fraction before giving up.
  double min_continuation_step = 1.0 / 1024.0;
  /// Multi-level solve with a fixed-step method (kRk4, kRk6, kRk8): a coarse problem with this
  /// many steps is converged first (to a scaled residual of 1e-9); a cold start then
  /// converges a middle level with twice as many steps (if 4 x this <= steps) and starts
  /// `integrator.steps` at the Richardson extrapolation of the two (O(h^p) term removed, p
  /// the method's order); a warm start without a Jacobian (or with warm_start_fine_only =
  /// false) adds the coarse solution's change to the previous fine solution. Newton on the
  /// fine level takes its (sensitivity) Jacobians from this coarse level, and from the fine
  /// level only if that one fails at a point. 0 disables (also when steps < 2 x this). Only
  /// the starting point and the Jacobians change: convergence is always tested on the fine
  /// problem.
  int coarse_steps = 4;
  /// Warm starts with a Jacobian skip the coarse level and iterate on the fine problem from
  /// the previous solution with the previous (Broyden-updated) Jacobian.
  bool warm_start_fine_only = true;
  /// Solve planar problems in the plane (docs/conventions.md "Planar reduction"): when the
  /// strings are straight with offsets on body x, the reference curvature is about body y,
  /// there is no tip constraint, the loads stay in the base frame's x-z plane (exact tests
  /// per solve), the method is fixed-step with flat kinematics and sensitivity Jacobians, and
  /// a warm start's unknowns lie in the plane, the IVP has 9 + n instead of 21 + n states and
  /// the Newton iteration 3 + n_tca instead of 6 + n_tca unknowns. The discretization is the
  /// same (results agree with the 3-D solve to round-off); the in-plane unknowns of a
  /// solution are reported in the 3-D layout with exact zeros elsewhere.
  bool planar_reduction = true;
  /// Centerline samples in results: 0 = every RK4 step node (64 intervals with CVODE);
  /// otherwise this many equal intervals (must be even, and divide `steps` for kRk4, kRk6, kRk8).
  int centerline_intervals = 0;
};

/// Outcome of one solve.
struct Summary {
  enum class Status {
    kConverged,           ///< ||r_scaled||_inf <= Options::tolerance
    kMaxIterations,       ///< max_iterations Newton steps done with ||r_scaled||_inf > tolerance
    kLineSearchFailed,    ///< max_line_search_steps halvings of the Newton step with a
                          ///< freshly computed Jacobian gave no Armijo decrease of
                          ///< ||r_scaled||^2 (or that Jacobian's IVP failed)
    kSingularJacobian,    ///< a freshly computed Jacobian's LU gave a non-finite step
    kContinuationFailed,  ///< the direct solve failed and the continuation step fell below
                          ///< Options::min_continuation_step (or the unloaded solve failed)
    kInitialPointFailed,  ///< the IVP or a TCA law failed at the initial guess
    kContactNotSettled,   ///< obstacles: the active set of the contact points still changed
                          ///< (or cycled) after max_iterations active-set Newton steps
    kNotRun,              ///< a default-constructed summary: no solve filled it
  };
  Status status = Status::kNotRun;
  int iterations = 0;          ///< Newton iterations over all levels and continuation steps
  int ivp_count = 0;           ///< IVP integrations (all levels; an augmented sensitivity
                               ///< IVP counts once, an FD Jacobian nx times)
  int continuation_steps = 0;  ///< 0 when the direct solve converged
  /// ||r_scaled||_inf (the scaling above, at the last Newton point; at the full load for the
  /// returned point after a failed continuation, +inf if the IVP or a TCA law fails there).
  double residual = 0.0;
  /// The residual both methods report (rod::Result::residual, docs/scenario-format.md): the
  /// largest unbalanced force of the tip conditions at the returned point and the full load
  /// (force and TCA rows F_c r, moment rows F_c L r / L, tip-constraint rows max(EA, GA) r)
  /// over characteristic_force_N; empty when the IVP or a TCA law fails there or no solve ran.
  std::optional<double> equilibrium_residual;
  double characteristic_force_N = 0.0;  ///< F_c of the solve's loads (rod::characteristic_force_N)
  double wall_time_s = 0.0;
  std::string message;  ///< empty when converged
  /// Global equilibrium: n(0) and m(0) (about p(0)) minus what the applied loads
  /// (gravity, tip wrench, string terminations) require [N], [N m], world frame.
  Eigen::Vector3d force_imbalance_W_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_imbalance_W_Nm = Eigen::Vector3d::Zero();
  /// True if the solve ran in the plane (Options::planar_reduction).
  bool planar = false;

  bool converged() const { return status == Status::kConverged; }
};

const char* to_string(Summary::Status s);

/// A solution (or a starting guess): unknowns and what warm starts reuse.
struct Solution {
  bool valid = false;        ///< false: solve starts from the initial guess (a cold solve)
  Eigen::VectorXd unknowns;  ///< x = (nu(0) - nu*, omega(0), T_tca..., tip reaction)
  /// d r_scaled / d x at (or near) `unknowns`; may be empty. After a planar solve
  /// (Summary::planar) it is the Jacobian of the in-plane unknowns (nu_x, nu_z - 1, omega_y,
  /// T_tca...), as are coarse_unknowns, coarse_jacobian and the path's unknowns; a solve
  /// ignores those fields when their size is not its own number of unknowns.
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd
      tip_state;  ///< y(L) of the last accepted IVP (3-D layout, also after a planar solve)
  /// Solution and Jacobian of the coarse level (Options::coarse_steps), for warm starts.
  Eigen::VectorXd coarse_unknowns;
  Eigen::MatrixXd coarse_jacobian;
  std::vector<double> tensions_N;     ///< per actuator (one string)
  std::vector<double> elongations_m;  ///< per actuator (one string)
  /// Obstacles (docs/conventions.md "Contact in the shooting method"): the contact
  /// multiplier lambda [N] of each (grid node, obstacle, candidate) pair, index
  /// ((k - 1) n_obstacles + o) n_candidates + j for node s_k (k = 1..steps; s_k = k L / steps
  /// on a uniform body), model obstacle o and contact candidate j of the section
  /// (rod::section_gaps: 1 for a circle, 8 for a rectangle); zero where open. A warm start
  /// takes its active set (lambda > 0) and multipliers from here. Empty without obstacles.
  std::vector<double> contact_lambda_N;

  /// A converged point of a sequence of warm-started solves (a sweep).
  struct PathPoint {
    Eigen::VectorXd actuation;  ///< the actuation as a flat vector (see ShootingSolver::solve)
    Eigen::VectorXd unknowns;
  };
  /// The last converged points (oldest first, at most ShootingSolver::kPathHistory), reset
  /// by a cold solve and cleared by a failed one: warm starts extrapolate along them.
  std::vector<PathPoint> path;
};

/// Shooting solver for one model. Holds a reference to the (constant) model, the
/// integrator and work buffers; not thread-safe, cheap to reuse across solves.
class ShootingSolver {
 public:
  /// Converged points kept in Solution::path: a warm start whose actuation continues a
  /// straight line through them (a sweep) starts from the polynomial extrapolation of the
  /// unknowns through up to this many points.
  static constexpr int kPathHistory = 4;

  /// Validates options; the model must outlive the solver.
  ShootingSolver(const rod::RodModel& model, const Options& options);
  ~ShootingSolver();
  ShootingSolver(ShootingSolver&&) noexcept;
  ShootingSolver& operator=(ShootingSolver&&) = delete;
  ShootingSolver(const ShootingSolver&) = delete;
  ShootingSolver& operator=(const ShootingSolver&) = delete;

  /// Solves the BVP for `loads`. If `solution.valid`, starts from it (warm start,
  /// reusing its Jacobian; when the loads, as the flat vector (per actuator: tension,
  /// then each segment's fraction and temperature; tip force, tip moment, gravity), lies on
  /// the straight line through the last points of `solution.path`, from the polynomial
  /// extrapolation of the unknowns along it with a fresh coarse-level Jacobian, falling back
  /// to the last solution if that start does not converge); else from initial_guess(), and
  /// if that start fails with gravity in the guess, from the guess without it.
  /// If that fails and Options::continuation, it steps the load fraction lambda from 0 to 1
  /// (tensions, tip wrench, gravity scaled by lambda; temperatures T_ref + lambda (T - T_ref))
  /// warm-starting each step, doubling the step after a success and halving it after a
  /// failure. On return `solution` holds the last accepted (finite) point. A load_scale
  /// other than 1 solves loads.applied(model) (rod/loads.hpp); so does make_result. The
  /// evaluation functions below (initial_guess, residual, ...) ignore load_scale.
  Summary solve(const rod::Loads& loads, Solution& solution);

  /// Integrates the solution once more with output and fills a result (tip pose,
  /// actuators, centerline samples, bending radius, summary fields, discretization).
  rod::Result make_result(const rod::Loads& loads, const Solution& solution,
                          const Summary& summary);

  /// The unknowns a cold solve starts from (docs/conventions.md "Initial guess"): the
  /// closed-form constant strains of the tensions, with the TCA tensions consistent with
  /// their closed-form elongations, bent further by gravity (a fixed point on a
  /// constant-strain arc; ignored if that does not converge); tip loads and reactions are
  /// not included (reactions 0).
  Eigen::VectorXd initial_guess(const rod::Loads& loads);

  /// Scaled residual at x (for tests); returns false if the IVP or a TCA law failed.
  bool residual(const rod::Loads& loads, const Eigen::VectorXd& x, Eigen::VectorXd& r);
  /// Jacobian of the scaled residual at x by Options::jacobian (for tests); false on failure.
  bool jacobian(const rod::Loads& loads, const Eigen::VectorXd& x, Eigen::MatrixXd& J);

  /// Scaled residual at x and the IVP end state y(L) (layout above); false on failure.
  bool residual_and_tip_state(const rod::Loads& loads, const Eigen::VectorXd& x, Eigen::VectorXd& r,
                              Eigen::VectorXd& tip_state);
  /// One augmented IVP at x: scaled residual r, its exact Jacobian J = dr/dx, y(L) and the
  /// forward sensitivities dy(L)/dx (state_dimension() x unknown_count()). Returns false
  /// when Options::jacobian is not kSensitivity (or it fell back to differences) or the IVP
  /// failed.
  bool tip_sensitivities(const rod::Loads& loads, const Eigen::VectorXd& x, Eigen::VectorXd& r,
                         Eigen::MatrixXd& J, Eigen::VectorXd& tip_state, Eigen::MatrixXd& dtip_dx);
  /// IVP state dimension (21 + actuators).
  int state_dimension() const;
  /// Number of unknowns (6 + TCA-driven actuators + tip-constraint reactions).
  int unknown_count() const;
  /// Characteristic force F_c [N] of the residual scaling.
  double characteristic_force_N() const;
  const Options& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Impl> reduced_;  ///< the planar reduction's solver (planar models only)
};

/// Convenience: solves the model's own loads and returns the result.
rod::Result solve(const rod::RodModel& model, const Options& options);

}  // namespace tcasim::cosserat
