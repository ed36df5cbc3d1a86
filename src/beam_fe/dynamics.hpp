#pragma once
/// Dynamics of the Simo-Reissner beam elements (beam_fe.hpp): the semi-discrete equations
/// of motion integrated by the generalized-alpha method on the Lie group (R^3 x SO(3))^nodes
/// ([Bruls2012]); docs/conventions.md "Beam FE dynamics".
///
/// Unknowns per free node: the world-frame velocity v_a = dp_a/dt and the body angular velocity
/// W_a (R_a' = R_a hat(W_a)). Equations of motion at t_{n+1}:
///   M vdot + (W_a x J_a W_a)_a + f_int(q, strain rates) - f_ext(q) = 0,
/// M the consistent translational mass int rho A N_a N_b ds (plus the tip mass at the tip
/// node), J_a the rotational inertia of node a by nodal quadrature (int N_a ds rho J, Simpson's
/// rule for quadratic elements), f_int the static element forces (strings as an internal
/// potential, closed coils and anchors as in statics) with Kelvin-Voigt stresses B_se e_t,
/// B_bt omega_t at every quadrature point. A TCA-driven string adds its tension T_i as an
/// unknown with the algebraic row T_i - F_tca(delta_i, temperatures at t_{n+1}) (the static
/// bordered row, coil contact included); the temperatures come from the loads, an electric
/// drive's from its thermal states advanced before the mechanics (rod::ElectricThermalStates).
/// Time step: the Newton unknown is the increment x = log(q_n^-1 q_{n+1}) / dt (a vector), with
/// q_{n+1} = q_n exp(dt x) and the Newmark and alpha relations giving a_{n+1}, v_{n+1} and
/// vdot_{n+1} as affine functions of x, followed by the TCA tensions at t_{n+1}; the Jacobian
/// is exact (step_residual for tests).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/trajectory.hpp"

namespace tcasim::beam_fe {

/// Options of the FE dynamics (validated by BeamDynamics' constructor: InputError naming the
/// field).
struct DynamicsOptions {
  int elements = 16;  ///< elements (>= 1)
  int order = 2;      ///< Lagrange order, 1 or 2
  Integration integration = Integration::kReduced;
  double dt_s = 2e-3;  ///< time step [s], > 0
  /// Spectral radius at infinite frequency of the generalized-alpha method, in [0, 1]:
  /// 1 is non-dissipative (the trapezoidal rule on linear problems), smaller values damp
  /// the high frequencies more (0: annihilated in one step).
  double rho_inf = 0.9;
  /// Converged when every force row |r_i| <= tolerance F_c and every moment row
  /// |r_i| <= tolerance F_c L (F_c = rod::characteristic_force_N of the loads at t = 0),
  /// plus the round-off floor of the rows (Discretization::round_off_floor, with the viscous
  /// stiffness c_e B of Kelvin-Voigt damping added to the elastic one).
  double tolerance = 1e-10;
  int max_iterations = 30;  ///< Newton iterations per time step
  /// Reuse the last factorization of the step Jacobian (chord iterations, across steps) while
  /// it contracts the residual by 4 per iteration; false: a fresh Jacobian every iteration.
  bool reuse_factorization = true;
  /// Kelvin-Voigt viscosity eta [Pa s], constant along s. Unset (the default): the model's
  /// body.material.viscosity_Pa_s, a constant or a profile along s (the mesh then has a node at
  /// each breakpoint of the profile), as cosserat::DynamicsOptions::viscosity_Pa_s.
  std::optional<double> viscosity_Pa_s;
  /// Point mass at the tip [kg] (inertia and weight). Unset (the default): the model's
  /// tip_mass_kg, as cosserat::DynamicsOptions::tip_mass_kg.
  std::optional<double> tip_mass_kg;
};

/// Outcome of the static initialization or of one time step.
struct BeamDynamicsSummary {
  enum class Status {
    kConverged,      ///< the residual is within DynamicsOptions::tolerance
    kMaxIterations,  ///< max_iterations Newton iterations without convergence
    kSingular,       ///< the iteration matrix could not be factorized
    kNonFinite,      ///< the residual or the Newton step is not finite
    kNotRun,
  };
  Status status = Status::kNotRun;
  int iterations = 0;
  double residual = 0.0;  ///< max scaled residual row (force rows / F_c, moment / (F_c L))
  std::string message;
  bool converged() const { return status == Status::kConverged; }
};

const char* to_string(BeamDynamicsSummary::Status s);

/// Generalized-alpha parameters of rho_inf ([Bruls2012] / Chung-Hulbert):
/// alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
/// beta = (gamma + 1/2)^2 / 4.
struct AlphaParameters {
  double alpha_m, alpha_f, gamma, beta;
};
AlphaParameters alpha_parameters(double rho_inf);

/// FE dynamics of one model: static initialization at t = 0, then time steps (of
/// DynamicsOptions::dt_s, or as set by set_time_step). Holds a
/// reference to the model (it must outlive the solver). Tension drives and TCA drives (by
/// temperature from the loads, or electric: thermal states advanced with each step), strings
/// anchored inside the body; a tip constraint is refused with DomainError (as in
/// cosserat::RodDynamics).
class BeamDynamics {
 public:
  BeamDynamics(const rod::RodModel& model, const DynamicsOptions& options);
  ~BeamDynamics();
  BeamDynamics(const BeamDynamics&) = delete;
  BeamDynamics& operator=(const BeamDynamics&) = delete;

  /// Static equilibrium under `loads` (at rest; beam_fe::solve, then Newton on this solver's
  /// residual); time is set to 0.
  BeamDynamicsSummary initialize(const rod::Loads& loads);
  /// Advances by dt_s under `loads` (the loads at the new time t + dt).
  BeamDynamicsSummary step(const rod::Loads& loads);

  /// Sets the size of the following time steps [s] (finite, > 0; InputError naming
  /// "dynamics.dt_s" otherwise). The integrator's history (q, v, vdot, a) is kept:
  /// generalized-alpha is a one-step method (docs/conventions.md "Variable time steps").
  void set_time_step(double dt_s);
  /// Estimated local (one-step) error of the last converged step(): the largest, over the
  /// nodes, of the position error estimate |e_p| [m] and L |e_theta| (rotation error times rod
  /// length), e = (beta - gamma/2 + 1/12) dt^2 (a_{n+1} - a_n) per node (docs/conventions.md
  /// "Variable time steps"). 0 before the first step.
  double local_error_m() const;
  /// The smallest time step the method takes [s]: 0 (any; the mesh is not tied to the step).
  double min_time_step_s() const { return 0.0; }
  /// Order p of the method: local error ~ dt^(p+1) (2).
  int error_order() const;
  /// Returns to the state just before the last step() call (converged or not): nodal state,
  /// velocities, accelerations and the alpha-history, time, TCA tensions, thermal states of
  /// electric drives, the Kelvin-Voigt history, the local error. One level only; a no-op
  /// before any step. The time step size stays as set.
  void undo_step();

  double time_s() const;
  double time_step_s() const;  ///< the size of the next step (DynamicsOptions::dt_s unless set)
  const State& state() const;  ///< nodal configuration of the last converged step
  const Discretization& discretization() const;
  /// Per free node (6 each): velocities (v_a world, W_a body) of the last converged step.
  /// (The TCA tensions follow in step_residual's unknowns, not here.)
  const Eigen::VectorXd& velocities() const;
  Eigen::Vector3d tip_position_W_m() const;
  Eigen::Matrix3d tip_rotation_W() const;
  /// Kinetic energy 1/2 v.M v + 1/2 sum W_a.J_a W_a + 1/2 m_tip |v_tip|^2 [J].
  double kinetic_energy_J() const;
  /// Potential energy of the current loads taken as constant [J]: strain energy (the element
  /// quadrature), minus the work potential of gravity (consistent nodal loads) and of the tip
  /// force (with the tip mass's weight), plus c_i T_i delta_i of the strings (tip moments are
  /// not included: not conservative in 3-D). Its gradient is the static residual.
  double potential_energy_J() const;
  /// Per actuator: tension of one string [N] (a TCA's: its unknown) and elongation [m].
  std::vector<double> tensions_N() const;
  std::vector<double> elongations_m() const;
  /// Per actuator, its segments' temperatures of the last converged step [K], base to tip (one
  /// for a TCA at a uniform temperature; empty for a tension drive): an electric drive's
  /// thermal states, else the loads' temperatures.
  std::vector<std::vector<double>> segment_temperatures_K() const;

  /// For tests: the step residual at unknowns x (6 per free node, then one tension per TCA)
  /// from the last converged step under `loads` (electric drives: at the current thermal
  /// states), scaled as the convergence test; with J, its exact Jacobian dr/dx.
  Eigen::VectorXd step_residual(const rod::Loads& loads, const Eigen::VectorXd& x,
                                Eigen::SparseMatrix<double>* J = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The trajectory row of the current state (rod/trajectory.hpp).
rod::TrajectoryRow trajectory_row(const BeamDynamics& dyn);

}  // namespace tcasim::beam_fe
