#pragma once
/// Dynamic cross-check of the two rod dynamics (cosserat::RodDynamics: shooting, BDF-alpha;
/// beam_fe::BeamDynamics: beam elements, Lie-group generalized-alpha) on one scenario, shared
/// by `tcasim compare --dynamic` and validate_dynamic_crosscheck (one implementation).
///
/// Both runs start from their own static state under the loads at t = 0 and follow the
/// scenario's time profiles (docs/scenario-format.md "Time profiles"), its viscosity and tip
/// mass; they write the tip at the same output times. The difference of two trajectories is
/// the largest Euclidean distance of the tips over the common output times [m] (world frame).
///
/// Time extrapolation: both schemes are second order in dt, so a run at dt and one at dt / 2
/// give p* = p(dt/2) + (p(dt/2) - p(dt)) / 3 at every common output time (Richardson, ratio 2,
/// order 2), a trajectory whose time error is of higher order; the difference of two
/// extrapolated trajectories is then the spatial and model difference.
///
/// Adaptive time steps (DynamicSettings::rtol): both methods run method::run_adaptive with the
/// settings of `tcasim simulate --rtol` (study::adaptive_options, the shooting grid of
/// study::dynamic_options) and land on the same output times k output_dt_s, where they are
/// compared.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rod/loads.hpp"
#include "rod/model.hpp"

namespace tcasim::crosscheck {

/// The two dynamics methods.
enum class DynamicMethod { kShooting, kFe };
const char* to_string(DynamicMethod m);  ///< "cosserat" or "fe"

/// Time grid and discretizations of one dynamic run (both methods).
struct DynamicSettings {
  double duration_s = 0.2;  ///< simulated time T [s], > 0
  double dt_s = 1e-3;       ///< time step [s], > 0 (T / dt rounded to whole steps)
  /// Output interval [s]: the tip is recorded every round(output_dt_s / dt_s) steps (>= 1) and
  /// at t = 0; 0: every step. Runs at different dt compare at the times they share.
  double output_dt_s = 0.0;
  /// Adaptive time steps instead of dt_s (which is then ignored): the relative tolerance of the
  /// local error per rod length, in (0, 1); output_dt_s (> 0) is then the output period.
  std::optional<double> rtol;
  double atol_m = 0.0;  ///< adaptive: absolute tolerance of the local error [m], >= 0
  /// The scenario's tip load acts at t = 0 only (released at t = 0+: a released cantilever).
  bool release_tip_load = false;
  // Shooting (cosserat::DynamicsOptions).
  /// RK4 steps along s; unset: cosserat::recommended_steps for dt.
  std::optional<int> steps;
  double alpha = -0.2;                ///< BDF-alpha parameter in [-0.5, 0]
  double shooting_tolerance = 1e-12;  ///< scaled residual (below the default 1e-10)
  // FE (beam_fe::DynamicsOptions).
  int elements = 32;
  int order = 2;
  double rho_inf = 0.9;         ///< generalized-alpha spectral radius at infinite frequency
  double fe_tolerance = 1e-12;  ///< scaled residual (below the default 1e-10)
  int max_iterations = 30;      ///< Newton iterations per step (both methods)
};

/// One method's trajectory.
struct DynamicRun {
  DynamicMethod method = DynamicMethod::kShooting;
  std::vector<double> t_s;               ///< output times [s], from 0
  std::vector<Eigen::Vector3d> tip_W_m;  ///< tip position at t_s [m]
  std::vector<double> kinetic_J;         ///< kinetic energy at t_s [J]
  std::vector<double> potential_J;       ///< potential energy of the loads at t_s [J]
  bool ok = false;                       ///< the static state and every step converged
  std::string message;                   ///< why it stopped (empty when ok)
  int grid_steps = 0;                    ///< shooting: RK4 steps along s used; FE: elements
  double wall_s = 0.0;                   ///< wall time of the run [s]
  long long steps_done = 0;              ///< accepted time steps
  long long steps_rejected = 0;          ///< adaptive: steps retried (error or Newton failure)
};

/// Runs one method (DomainError when the method does not support the model, InputError for
/// bad settings; a failed step is an outcome: ok = false with the message, rows before it
/// kept).
DynamicRun run_dynamics(const rod::RodModel& model, DynamicMethod method,
                        const DynamicSettings& settings);

/// Empty when the FE dynamics takes the model, else its reason (the DomainError's text).
std::string fe_dynamics_unsupported(const rod::RodModel& model);

/// max_t |a(t) - b(t)| over the output times both runs share (within 1e-9 of the duration).
struct TrajectoryDifference {
  double max_m = 0.0;      ///< largest tip distance [m] (NaN when no time is shared)
  double at_t_s = 0.0;     ///< where it occurs [s]
  std::size_t shared = 0;  ///< number of shared output times
};
TrajectoryDifference trajectory_difference(const DynamicRun& a, const DynamicRun& b);

/// The Richardson extrapolation in dt of a run at dt (`coarse`) and one at dt / 2 (`fine`) at
/// their shared output times (see the header); energies and grid from `fine`. ok only if both
/// are.
DynamicRun extrapolate_in_time(const DynamicRun& coarse, const DynamicRun& fine);

/// Per-time CSV of a comparison: t_s, the reference's tip (shooting_tip_x_m, ...), then per
/// other run `<label>_tip_x_m, <label>_tip_y_m, <label>_tip_z_m, <label>_diff_m` at the
/// reference's output times (nan where a run has no sample), and the energies of the
/// reference and each run (`<label>_kinetic_J`, `<label>_potential_J`).
std::string dynamic_csv(const DynamicRun& reference, const std::vector<DynamicRun>& others,
                        const std::vector<std::string>& labels);

}  // namespace tcasim::crosscheck
