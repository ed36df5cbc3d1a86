#pragma once
/// Cosserat rod dynamics by shooting: the rod PDE semi-discretized in time by the implicit
/// BDF-alpha formula ([Till2019]), each time step's boundary-value problem in s solved by
/// multiple shooting with fixed-step RK4 on a fixed grid (docs/conventions.md "Rod dynamics
/// (shooting method)").
///
/// State per point (dimension 24 + n_actuators), body-frame quantities in B, SI:
///   y = ( p_W [0,3), R_WB [3,12) column-major, N_B [12,15), M_B [15,18), q_B [18,21),
///         w_B [21,24), delta_i [24, 24 + n), T_j [24 + n, 24 + n + n_tca) )
/// with N, M the internal force and moment of the section including the strings' tensions
/// (N = n + sum c_i T_i qh_i, M = m + sum c_i T_i r_i x qh_i), q and w the linear and
/// angular velocity, delta_i the string elongations, T_j the tension of one string of the
/// j-th TCA-driven actuator (constant along s; none for tension drives).
/// Multiple shooting: M intervals of S RK4 steps each (N = M S steps of h = L / N on a uniform
/// body; a body whose properties vary along s gets a grid node at every breakpoint of its
/// profiles and steps of at most L / N on each piece between them); unknowns
/// (N_B, M_B) at s = 0 and the whole state at the start of every other interval; residual:
/// continuity at each interior node and the tip balance. Newton (chord iterations with the
/// last factorization; a fresh Jacobian when they contract slowly) with the exact Jacobian
/// (forward sensitivities of each interval), factorized densely (partial pivoting) up to
/// kDenseUnknowns unknowns (dynamics_impl.hpp), by Eigen's SparseLU above.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rod/loads.hpp"
#include "rod/model.hpp"

namespace tcasim::cosserat {

/// Options of the rod dynamics (validated by RodDynamics' constructor: InputError naming the
/// field).
struct DynamicsOptions {
  int steps = 40;     ///< RK4 steps along s (N; the grid has N + 1 points), >= 1
  int intervals = 0;  ///< shooting intervals M (must divide steps); 0: automatic
  /// Automatic intervals: the fewest M dividing `steps` whose interval length l satisfies
  /// l kappa <= max_interval_growth, kappa the fastest spatial growth rate of the step's
  /// linearized problem (docs/conventions.md): each interval amplifies errors by <= e^this.
  double max_interval_growth = 5.0;
  double dt_s = 2e-3;   ///< time step [s], > 0 (RodDynamics::set_time_step changes it)
  double alpha = -0.2;  ///< BDF-alpha parameter in [-0.5, 0] (0: BDF2, -0.5: trapezoidal)
  /// Converged when the scaled residual (docs/conventions.md) satisfies ||r||_inf <= this.
  double tolerance = 1e-10;
  int max_iterations = 30;  ///< Newton (chord) iterations per time step
  /// Kelvin-Voigt viscosity eta [Pa s], constant along s. Unset (the default): the model's
  /// body.material.viscosity_Pa_s (a constant or a profile along s).
  std::optional<double> viscosity_Pa_s;
  /// Point mass at the tip [kg]. Unset (the default): the model's tip_mass_kg.
  std::optional<double> tip_mass_kg;
  /// Scheme along s: kRk4 (fourth order, the default), or kEuler (forward Euler, first order,
  /// on the same grid and history points: only for measuring what a first-order spatial scheme
  /// such as [Till2019]'s reaches; energies then use the left-point rule).
  enum class SpatialScheme { kRk4, kEuler };
  SpatialScheme scheme = SpatialScheme::kRk4;
};

/// RK4 steps h along s must satisfy h kappa <= kMaxStepGrowth (kappa: spatial_growth_rate):
/// coarser grids misrepresent the step's fast spatial modes and the time stepping goes
/// unstable (measured on the steel cantilever: h kappa = 1.34 agrees with a fine grid to
/// 1e-7 m, 2.0 diverges).
inline constexpr double kMaxStepGrowth = 1.5;

/// Fastest spatial growth rate kappa [1/m] of one time step's linearized problem
/// (docs/conventions.md): max of bending (rho A / EI)^(1/4) sqrt(c0), axial and shear
/// sqrt(rho A / K_se) c0 and torsion sqrt(rho J_p / GJ) c0, c0 the BDF-alpha coefficient.
double spatial_growth_rate(const rod::RodModel& model, const DynamicsOptions& options);

/// RK4 steps for `options.dt_s`: max(20, ceil(L kappa)) (h kappa <= 1), even.
int recommended_steps(const rod::RodModel& model, const DynamicsOptions& options);

/// Outcome of the static initialization or of one time step.
struct DynamicsSummary {
  enum class Status {
    kConverged,         ///< ||r_scaled||_inf <= DynamicsOptions::tolerance
    kMaxIterations,     ///< max_iterations iterations with ||r_scaled||_inf > tolerance
    kNotConverging,     ///< a fresh Jacobian and 6 halvings of its step gave no decrease
    kSingularJacobian,  ///< the LU factorization of the Jacobian failed (or a step not finite)
    kNonFinite,         ///< the state became non-finite (or a section's constitutive
                        ///< solve failed) at the starting point
    kNotRun,
  };
  Status status = Status::kNotRun;
  int iterations = 0;  ///< Newton iterations
  int jacobians = 0;   ///< Jacobians computed and factorized
  double residual = 0.0;
  std::string message;  ///< why, when not converged
  bool converged() const { return status == Status::kConverged; }
};

const char* to_string(DynamicsSummary::Status s);

/// Rod dynamics of one model: static initialization at t = 0, then time steps (of dt_s, or of
/// the sizes set by set_time_step(); a step can be undone and retried smaller).
/// Holds a reference to the model (it must outlive the solver). Tension drives and TCA
/// drives (by temperature from the loads, or electric: thermal states advanced with each
/// step; docs/conventions.md "TCAs in rod dynamics").
class RodDynamics {
 public:
  RodDynamics(const rod::RodModel& model, const DynamicsOptions& options);
  ~RodDynamics();
  RodDynamics(const RodDynamics&) = delete;
  RodDynamics& operator=(const RodDynamics&) = delete;

  /// Static equilibrium under `loads` (at rest, with this solver's discretization), started
  /// from the static shooting solver's solution; time is set to 0.
  DynamicsSummary initialize(const rod::Loads& loads);
  /// Advances by dt_s under `loads` (the loads at the new time t + dt).
  DynamicsSummary step(const rod::Loads& loads);

  /// Sets the size of the following time steps [s] (finite, > 0; InputError naming
  /// "dynamics.dt_s" otherwise). The integrator's history is kept: the next steps use the
  /// variable-step coefficients (docs/conventions.md). The grid along s stays as constructed:
  /// a step too small for it (h kappa > kMaxStepGrowth) is refused naming "dynamics.dt_s";
  /// with automatic intervals, more intervals are chosen when the growth rule needs them.
  void set_time_step(double dt_s);
  /// Estimated local (one-step) error of the last converged step(): the largest, over the grid
  /// points, of the position error estimate |e_p| [m] and L |e_theta| (rotation error estimate
  /// times the rod length). 0 before the first step.
  double local_error_m() const;
  /// The smallest time step this solver's grid along s resolves [s]: where h kappa reaches
  /// kMaxStepGrowth (kappa grows as the step shrinks; set_time_step refuses smaller ones).
  double min_time_step_s() const;
  /// Order p of the method: local error ~ dt^(p+1) (the step-size controller uses it).
  int error_order() const;
  /// Returns to the state just before the last step() call (converged or not): states, time,
  /// history, thermal states of electric drives, warm-start data. One level only; a no-op before
  /// any step. Then a smaller set_time_step() and step() retries it.
  void undo_step();

  double time_s() const;
  double time_step_s() const;   ///< the size of the next step (dt_s or set_time_step's)
  int intervals() const;        ///< M
  int state_dimension() const;  ///< 24 + actuators + TCA-driven actuators
  /// States at the grid points of the last converged solve (grid_s_m(); s_i = i L / N on a
  /// uniform body).
  const std::vector<Eigen::VectorXd>& grid_states() const;
  /// Arc lengths of the grid points [m], increasing from 0 to L.
  const std::vector<double>& grid_s_m() const;
  /// RK4 steps along s actually used (DynamicsOptions::steps on a uniform body; at least that
  /// on a varying one, whose breakpoints are grid nodes).
  int steps() const;
  Eigen::Vector3d tip_position_W_m() const;
  Eigen::Matrix3d tip_rotation_W() const;
  /// World positions of the model's probes [m], in its order (each probe's s is a grid node).
  std::vector<Eigen::Vector3d> probe_positions_W_m() const;
  /// Kinetic energy 1/2 int (rho A |q|^2 + w . rho J w) ds + 1/2 m_tip |q(L)|^2 [J].
  double kinetic_energy_J() const;
  /// Potential energy of the current loads taken as constant [J]: strain energy
  /// 1/2 int (e . K_se e + (omega - omega*) . K_bt (omega - omega*)) ds, minus the work
  /// potential of gravity and of the tip force, plus c_i T_i delta_i of the strings (tip
  /// moments are not included: they are not conservative in 3-D).
  double potential_energy_J() const;
  /// Per actuator: tension of one string [N] and elongation [m].
  std::vector<double> tensions_N() const;
  std::vector<double> elongations_m() const;
  /// Per actuator, its segments' temperatures of the last solve [K], base to tip (one for a
  /// TCA at a uniform temperature; empty for a tension drive): an electric drive's thermal
  /// states, else the loads' temperatures.
  std::vector<std::vector<double>> segment_temperatures_K() const;

  /// For derivative tests: the Newton system of the last solve (the last step's, or the static
  /// initialization's) at scaled unknowns u, u_i = z_i / scale_i with z = ((N_B, M_B) and the
  /// TCA tensions at s = 0, then the whole state at the start of each further interval): the
  /// scaled residual r and, with J, its Jacobian dr/du (the matrix Newton factorizes). False
  /// where the residual cannot be evaluated. The next step starts with a fresh Jacobian.
  bool newton_system(const Eigen::VectorXd& u, Eigen::VectorXd& r, Eigen::MatrixXd* J);
  /// The scaled unknowns u of the last converged solve (newton_system).
  Eigen::VectorXd scaled_unknowns() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tcasim::cosserat
