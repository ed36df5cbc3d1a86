#pragma once
/// Rod dynamics by either method with one call shape (method/method.hpp says why this layer
/// exists): cosserat::RodDynamics (shooting in s, BDF-alpha in t) or beam_fe::BeamDynamics
/// (beam elements, Lie-group generalized-alpha), chosen by the options' type, and the one time
/// loop that drives either (`tcasim simulate`, `compare --dynamic`, Python, the validation).
#include <Eigen/Core>
#include <functional>
#include <iosfwd>
#include <limits>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "beam_fe/dynamics.hpp"
#include "cosserat/dynamics.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"
#include "rod/trajectory.hpp"

namespace tcasim::method {

/// A dynamics method with its settings. Both take the scenario's viscosity and tip mass
/// unless their options replace them (DynamicsOptions::viscosity_Pa_s, tip_mass_kg).
using DynamicOptions = std::variant<cosserat::DynamicsOptions, beam_fe::DynamicsOptions>;

/// "cosserat" or "fe".
const char* name(const DynamicOptions& options);

/// Outcome of the static initialization or of one time step, the same for both methods.
struct StepSummary {
  bool converged = false;
  std::string status = "not_run";  ///< the method's status name (to_string of its summary)
  int iterations = 0;              ///< Newton iterations
  std::string message;             ///< why, when not converged
};

/// The dynamics of one model by either method: the static state at t = 0, then time steps of
/// the options' dt_s. Holds a reference to the model, which must outlive it. The constructor
/// validates the options (InputError naming `dynamics.<field>`) and refuses what the method
/// cannot take (DomainError, e.g. a tip constraint).
class DynamicSolver {
 public:
  DynamicSolver(const rod::RodModel& model, const DynamicOptions& options);
  ~DynamicSolver();
  DynamicSolver(const DynamicSolver&) = delete;
  DynamicSolver& operator=(const DynamicSolver&) = delete;

  /// Static equilibrium under `loads` (at rest); time is set to 0.
  StepSummary initialize(const rod::Loads& loads);
  /// Advances by one time step under `loads` (the loads at the new time).
  StepSummary step(const rod::Loads& loads);

  /// Sets the size of the following time steps [s] (finite, > 0; InputError naming
  /// "dynamics.dt_s" otherwise); the method's history is kept.
  void set_time_step(double dt_s);
  /// Estimated local (one-step) error of the last converged step [m]: positions, and
  /// rotations times the rod length (the method's local_error_m); 0 before the first step.
  double local_error_m() const;
  /// Order p of the method in time: local error ~ dt^(p+1).
  int error_order() const;
  /// The smallest step the method can take [s]: the shooting method's grid along s resolves
  /// the fast spatial modes of steps down to this (cosserat::RodDynamics::min_time_step_s);
  /// 0 for the FE.
  double min_time_step_s() const;
  /// Returns to the state just before the last step() call (one level; the method's
  /// undo_step).
  void undo_step();
  /// The model's rod length L [m] (the scale of the relative tolerance).
  double rod_length_m() const;

  double time_s() const;
  double time_step_s() const;  ///< the size of the next (or last) time step [s]
  Eigen::Vector3d tip_position_W_m() const;
  double kinetic_energy_J() const;
  /// Potential energy of the current loads taken as constant [J] (each method's definition:
  /// cosserat::RodDynamics / beam_fe::BeamDynamics::potential_energy_J).
  double potential_energy_J() const;
  /// The trajectory row of the current state (rod/trajectory.hpp), probes included.
  rod::TrajectoryRow row() const;
  /// The current shape as a result record (centerline, tip frame) for VTK frames.
  rod::Result frame() const;
  /// The spatial grid: shooting RK4 steps along s, or FE elements.
  int grid_size() const;
  const char* method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The loads of the scenario at time t [s]: its time profiles (tensions, temperatures, tip
/// wrench) at t, the static state at t = 0 (docs/scenario-format.md "Time profiles"); with
/// `release_tip_load` the tip wrench acts at t = 0 only (a released cantilever). An electric
/// drive's temperatures are each solver's thermal states.
rod::Loads loads_at(const rod::RodModel& model, double t_s, bool release_tip_load);

/// The one time loop of both methods: the static state under loads_at(0), then `steps` steps
/// to t = k dt (dt = the solver's time step); on_output(solver) at t = 0, every
/// `output_every`-th step and the last; on_step(k) after each converged step. A failed solve
/// ends the loop (the outputs before it were delivered) with status and message:
/// "static initial state did not converge (STATUS): ..." or "time step to t = T s failed
/// (STATUS): ...".
rod::TrajectoryOutcome run(DynamicSolver& solver, const rod::LoadsAt& loads_at, long long steps,
                           long long output_every,
                           const std::function<void(const DynamicSolver&)>& on_output,
                           const std::function<void(long long)>& on_step = {});

/// Error-controlled time steps of run_adaptive (docs/scenario-format.md "Trajectory file").
struct AdaptiveOptions {
  double rtol = 1e-4;   ///< relative tolerance of the local error, per rod length, in (0, 1)
  double atol_m = 0.0;  ///< absolute tolerance of the local error [m], >= 0
  double output_every_s = 0.0;  ///< output period [s], > 0 (and the end time)
  /// The first step's size [s], > 0, and the restart size after a breakpoint.
  double dt_initial_s = 1e-6;
  double dt_min_s = 1e-12;  ///< a step size below this ends the run [s], > 0
  double dt_max_s = std::numeric_limits<double>::infinity();  ///< largest step size [s]
  /// Times in (0, duration) the steps land on: the jumps of the scenario's time profiles
  /// (time_breakpoints), where the solution is not smooth.
  std::vector<double> breakpoints_s;
  long long max_steps = 100'000'000;  ///< accepted plus retried steps before giving up
};

/// The times in (0, t_end_s) where a time profile of `model` (tensions, temperatures,
/// electric inputs, tip wrench) or its slope jumps, increasing, without repeats.
std::vector<double> time_breakpoints(const rod::RodModel& model, double t_end_s);

/// The time loop with error-controlled steps: the static state under loads_at(0), then steps
/// to t = duration_s. Error norm err = local_error_m / (atol_m + rtol L); a step with err <= 1 is
/// accepted, else undone and retried; the next size is dt clamp(0.9 err^(-1/(p+1)), 0.2, 5)
/// (at most dt_max_s); a step whose Newton iteration fails is undone and retried at dt / 4.
/// Steps land exactly on the output times k output_every_s and duration_s (the step is
/// shortened, or halved when less than two remain; the proposal is kept for the step after) and
/// on breakpoints_s. At t = 0 and after each breakpoint the steps restart from dt_initial_s,
/// growing at most 1.5 per step for 20 steps (the jump makes the history inconsistent).
/// on_output(solver, dt) at t = 0 (dt = 0) and each output time (dt the
/// step that reached it); on_step(t) after each accepted step. A step size below dt_min_s or
/// more than max_steps steps end the run (status "dt-min" or "max-steps") as a failed step:
/// "time step to t = T s failed (STATUS): ...". The counts of accepted, rejected and failed
/// steps are in the outcome.
rod::TrajectoryOutcome run_adaptive(
    DynamicSolver& solver, const rod::LoadsAt& loads_at, double duration_s,
    const AdaptiveOptions& options,
    const std::function<void(const DynamicSolver&, double dt_s)>& on_output,
    const std::function<void(double t_s)>& on_step = {});

/// run() writing the trajectory CSV of docs/scenario-format.md "Trajectory file": the header,
/// a row per output, and on failure a last line "# " + the message.
rod::TrajectoryOutcome write_trajectory(DynamicSolver& solver, const rod::RodModel& model,
                                        const rod::LoadsAt& loads_at, long long steps,
                                        long long output_every, std::ostream& os);

}  // namespace tcasim::method
