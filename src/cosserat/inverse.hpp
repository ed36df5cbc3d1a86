#pragma once
/// Inverse kinetostatics ([Pawlowski2019] Section IV, after [Rucker2011b]): tip
/// Jacobian and compliance at a converged shooting solution, target tip position ->
/// actuation (temperatures, or tensions for tension drives), and the grasp temperature of a
/// finger whose tip is blocked by an object (Eqs. (43)-(44)).
///
/// Tip pose derivatives: rows 0-2 are d p_W(L) (world frame, m), rows 3-5 the world-frame
/// rotation increment vee(dR R^T) of the tip frame (rad). Actuation variables q: the
/// (uniform) temperature of a TCA actuator [K], or the tension of one string of a tension
/// drive [N]. Tip wrench W = (F_e,W [N], M_e,W [N m]) applied to the rod.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "cosserat/shooting.hpp"
#include "rod/model.hpp"

namespace tcasim::cosserat {

/// How E_u, B_u of [Pawlowski2019] Eqs. (41)-(42) are obtained at the converged unknowns u.
enum class TipDerivativeMethod {
  /// The shooting solver's forward sensitivities dy/du (one augmented IVP, exact for the
  /// RK4 map); E_q, B_q of temperatures and E_W, B_W are analytic (temperatures and the tip
  /// wrench enter only the tip conditions); a tension drive's column by central differences.
  kSensitivity,
  /// [Pawlowski2019] Eqs. (41)-(42) literally: one IVP per perturbed u, q and W component
  /// (forward differences, step sqrt(eps) x scale: about 1e-8 relative).
  kForwardDifference,
  /// As kForwardDifference with central differences (step eps^(1/3) x scale: about 1e-10).
  kCentralDifference,
};

/// Tip Jacobian J = dX/dq and compliance C = dX/dW (X = tip position and rotation).
struct TipDerivatives {
  Eigen::MatrixXd J;          ///< 6 x q: rows d p_W [m/K or m/N], d theta_W [rad/K or rad/N]
  Eigen::MatrixXd C;          ///< 6 x 6: columns F_e,W (x, y, z) [per N], M_e,W [per N m]
  Eigen::MatrixXd du_dq;      ///< -B_u^-1 B_q: first-order change of the shooting unknowns
  Eigen::MatrixXd B_u;        ///< d r_scaled / d u at the solution (a Newton Jacobian to reuse)
  Eigen::VectorXd tip_state;  ///< y(L) at the solution (shooting.hpp layout)
  int ivp_count = 0;          ///< IVP integrations used (an augmented IVP counts once)
};

/// [Pawlowski2019] Eqs. (41)-(42): J = E_q - E_u B_u^-1 B_q, C = E_W - E_u B_u^-1 B_W at
/// the converged `solution` of `actuation`. `variables` are actuator indices (model order).
/// The model must have no tip constraint (J and C describe a free tip). Returns false if an
/// IVP failed or B_u is singular. With obstacles `method` is not used: J and C are central
/// differences of warm-started contact solves (the sensitivities do not carry the contact
/// multipliers), du_dq is zero; false if one of them does not converge.
bool tip_derivatives(ShootingSolver& solver, const rod::RodModel& model,
                     const rod::Loads& actuation, const Solution& solution,
                     const std::vector<int>& variables, TipDerivativeMethod method,
                     TipDerivatives& out);

/// Lower and upper bound of each actuation variable: a TCA from its material's reference
/// (ambient) temperature to the smaller of its valid-range maximum and `max_temperature_K`
/// (NaN: none); a tension drive from 0 (a string cannot push) to `max_tension_N`.
void actuation_bounds(const rod::RodModel& model, const std::vector<int>& variables,
                      double max_temperature_K, double max_tension_N, Eigen::VectorXd& lower,
                      Eigen::VectorXd& upper);

/// Options of the target solve (validated by solve_inverse: InputError naming the field).
struct InverseOptions {
  std::vector<int> actuators;  ///< actuation variables (model indices); empty = all actuators
  /// Which tip position components (world x, y, z) are targeted (e.g. a 2D target).
  std::array<bool, 3> components{{true, true, true}};
  /// Optional tip orientation target R_WB; its error vee(log(R_target R^T)) is weighted by
  /// the body length (so radians count like L metres).
  std::optional<Eigen::Matrix3d> target_R_WB;
  double max_temperature_K = std::numeric_limits<double>::quiet_NaN();  ///< NaN: material max
  double max_tension_N = std::numeric_limits<double>::infinity();
  /// Converged: targeted position distance <= this (and orientation error x L <= this) [m].
  double tolerance_m = 1e-10;
  int max_iterations = 60;
  TipDerivativeMethod method = TipDerivativeMethod::kSensitivity;
};

/// Outcome of a target solve.
struct InverseResult {
  enum class Status {
    kConverged,      ///< targeted error <= InverseOptions::tolerance_m
    kUnreachable,    ///< a bounded least-squares optimum with error > tolerance: the
                     ///< projected gradient |J^T e| <= kStationarity |J| |e| (or no decrease
                     ///< possible); distance_m is the residual distance
    kMaxIterations,  ///< max_iterations accepted steps without either test
    kForwardFailed,  ///< a forward solve (or J) failed at the starting point
  };
  Status status = Status::kForwardFailed;
  std::string message;
  std::vector<int> actuators;  ///< the variables, model indices
  Eigen::VectorXd values;      ///< temperature [K] (TCA) or tension [N] per variable
  std::vector<bool> at_bound;  ///< variable held at a bound at the end
  Eigen::Vector3d tip_position_W_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d tip_R_WB = Eigen::Matrix3d::Identity();
  double distance_m = 0.0;  ///< targeted position error norm at the end
  double orientation_error_rad = 0.0;
  int iterations = 0;      ///< accepted steps
  int forward_solves = 0;  ///< BVP solves (accepted and rejected trials)
  bool converged() const { return status == Status::kConverged; }
};

const char* to_string(InverseResult::Status s);

/// Target tip position -> actuation by damped, bounded Gauss-Newton on Eq. (40)
/// (Levenberg-Marquardt with a scaled damping, an active set for the bounds, minimum-norm
/// steps for redundant actuation). Starts from `actuation` (values clamped into the bounds)
/// and `solution` (warm start if valid); on return both hold the final point.
InverseResult solve_inverse(ShootingSolver& solver, const rod::RodModel& model,
                            const Eigen::Vector3d& target_W_m, const InverseOptions& options,
                            rod::Loads& actuation, Solution& solution);

/// Grasp problem: one finger of an n-finger gripper, tip held by the object along the
/// model's tip_constraint normal (pointing from the finger toward the object).
struct GraspOptions {
  double mass_kg = 0.0;   ///< m, the grasped mass
  double friction = 0.0;  ///< mu between finger and object
  int fingers = 2;        ///< n
  double max_temperature_K = std::numeric_limits<double>::quiet_NaN();  ///< NaN: material max
  double temperature_tolerance_K = 1e-7;  ///< Eq. (43) iteration: stop when |dT| <= this
  int max_iterations = 50;
  TipDerivativeMethod method = TipDerivativeMethod::kSensitivity;
  bool cross_check = true;  ///< also root-find T on the blocked-tip forward solve
};

/// Outcome of a grasp solve.
struct GraspResult {
  bool converged = false;  ///< Eq. (43) iteration converged (and the cross-check, if run)
  std::string message;
  double required_force_N = 0.0;  ///< [Pawlowski2019] Eq. (44): m g / (mu n)
  double temperature_K = 0.0;     ///< Eq. (43) iterated to convergence
  int iterations = 0;
  std::optional<double> root_temperature_K;  ///< bracketed root of the blocked-tip solve
  int root_evaluations = 0;
  double blocked_normal_force_N = 0.0;  ///< blocked-tip forward solve at temperature_K
  Eigen::Vector3d tip_position_W_m = Eigen::Vector3d::Zero();  ///< at temperature_K
};

/// Grasp temperature of a finger: the TCA temperature at which the blocked tip pushes the
/// object with the normal force m g / (mu n) ([Pawlowski2019] Eqs. (43)-(44)). The model
/// needs exactly one TCA actuator and a tip_constraint with a normal (InputError otherwise).
/// Normal force = -(reaction . normal): the object pushes the finger back.
GraspResult solve_grasp(const rod::RodModel& model, const Options& shooting_options,
                        const GraspOptions& options);

/// Normal contact force of the blocked finger at temperature t_K (one forward solve of the
/// constrained model); NaN if it does not converge. `solution` warm-starts (in/out).
double blocked_normal_force_N(ShootingSolver& constrained_solver, const rod::RodModel& model,
                              double t_K, Solution& solution);

}  // namespace tcasim::cosserat
