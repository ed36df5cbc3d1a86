#pragma once
/// One simulation of rod dynamics from the static state at t = 0 (docs/scenario-format.md
/// "Trajectory file"), by the shooting method (cosserat/dynamics.hpp) or the beam FE
/// (beam_fe/dynamics.hpp): the work of `tcasim simulate` and tcasim.simulate, through
/// method::DynamicSolver and the one time loop method::run (method/dynamics.hpp).
#include <functional>
#include <optional>
#include <string>

#include "method/dynamics.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"
#include "rod/trajectory.hpp"
#include "study/options.hpp"

namespace tcasim::study {

/// The options of `tcasim simulate` (its flags; tcasim.simulate's keywords).
struct SimulationOptions {
  std::string method = "cosserat";  ///< "cosserat" or "fe"
  double duration_s = 0.0;          ///< simulated time T [s], > 0
  double dt_s = 0.0;                ///< fixed time step [s], > 0 (round(T / dt) steps)
  long long output_every = 1;       ///< a row every K-th step (and t = 0, the last step)
  /// Adaptive time steps instead of dt_s (method::run_adaptive): the relative tolerance of the
  /// local error per rod length, in (0, 1); with it output_every_s is required and dt_s and
  /// output_every are refused.
  std::optional<double> rtol;
  std::optional<double> atol_m;          ///< adaptive: absolute tolerance [m], >= 0 (default 0)
  std::optional<double> output_every_s;  ///< adaptive: a row every this many seconds, in (0, T]
  long long max_iterations = 30;         ///< Newton iterations per time step, in [1, 1000]
  bool release_tip_load = false;         ///< the scenario's tip load acts at t = 0 only
  std::optional<double> viscosity_Pa_s;  ///< overrides body.material.viscosity_Pa_s [Pa s]
  std::optional<double> tip_mass_kg;     ///< overrides tip_mass_kg [kg]
  double alpha = -0.2;                   ///< cosserat: BDF-alpha parameter in [-0.5, 0]
  /// cosserat: RK4 steps along s, in [1, kMaxSteps]; absent: cosserat::recommended_steps
  std::optional<long long> steps;
  long long elements = 16;  ///< fe: number of elements, in [1, kMaxElements]
  long long order = 2;      ///< fe: element order, 1 or 2
  double rho_inf = 0.9;     ///< fe: generalized-alpha spectral radius at infinity, in [0, 1]
};

/// Checks duration, time step and BDF-alpha parameter (InputError naming the option in
/// `style`); returns the number of time steps round(duration_s / dt_s), in [1, kMaxTimeSteps].
long long check_time_options(double duration_s, double dt_s, double alpha, OptionNames style);

/// Checks the options' ranges (InputError naming the option in `style`, its value and the
/// rule); returns the number of time steps round(duration_s / dt_s), or with adaptive steps
/// (rtol) the number of output rows after t = 0. The rules of the time grid and both methods'
/// options, also for `tcasim compare --dynamic`.
long long check_simulation_options(const SimulationOptions& o, OptionNames style);

/// What a simulation reports while it runs; every callback is optional.
struct SimulationHooks {
  std::function<void(const rod::TrajectoryRow&)> on_row;  ///< each output row, in order
  /// The shape at each output row (centerline, tip frame; for VTK frames); only built when set.
  std::function<void(const rod::Result&)> on_frame;
  /// After each (accepted) time step: steps done of the total, or with adaptive steps output
  /// periods done (fractions rounded down) of the total.
  std::function<void(long long done, long long total)> on_step;
};

/// The method and its settings of checked options `o`: the scenario's viscosity and tip mass
/// unless the options replace them; the shooting grid cosserat::recommended_steps unless
/// `steps` is given.
method::DynamicOptions dynamic_options(const rod::RodModel& model, const SimulationOptions& o);
/// The settings of method::run_adaptive of checked adaptive options `o`: the first step
/// min(output_every_s, 1e-6 duration_s), dt_min_s = 1e-12 duration_s, the jumps of the
/// scenario's time profiles as breakpoints, at most kMaxTimeSteps steps.
method::AdaptiveOptions adaptive_options(const rod::RodModel& model, const SimulationOptions& o);
/// Runs the simulation of `model` (checked options; InputError in `style` for what the
/// dynamics refuses). A failed step is an outcome (ok false with the message), not an error.
/// Adaptive steps: rows carry dt_s (TrajectoryRow::dt_s).
rod::TrajectoryOutcome simulate(const rod::RodModel& model, const SimulationOptions& o,
                                const SimulationHooks& hooks,
                                OptionNames style = OptionNames::kPython);

}  // namespace tcasim::study
