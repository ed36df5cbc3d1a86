#pragma once
/// The trajectory of a simulation (docs/scenario-format.md "Trajectory file"): one row type and
/// one CSV format for both methods' dynamics (cosserat::RodDynamics, beam_fe::BeamDynamics);
/// the one time loop that drives either is method::run (method/dynamics.hpp).

#include <Eigen/Core>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "rod/loads.hpp"
#include "rod/model.hpp"

namespace tcasim::rod {

/// The state of one output time.
struct TrajectoryRow {
  double t_s = 0.0;                                   ///< time [s]
  Eigen::Vector3d tip_W_m = Eigen::Vector3d::Zero();  ///< tip position [m], world frame
  double kinetic_energy_J = 0.0;                      ///< kinetic energy [J]
  std::vector<double> tensions_N;                     ///< per actuator: tension of one string [N]
  std::vector<double> elongations_m;                  ///< per actuator: its elongation [m]
  /// Per actuator its temperatures [K] (one per segment; empty: a tension drive). May be
  /// empty altogether (no actuator has any).
  std::vector<std::vector<double>> temperatures_K;
  std::vector<Eigen::Vector3d> probes_W_m;  ///< per probe of the model its position [m]
  /// Adaptive time steps only: the size of the last step taken [s] (0 at t = 0); the last
  /// column when set.
  std::optional<double> dt_s;
};

/// The row of a dynamics object's current state (Dyn: time_s, tip_position_W_m,
/// kinetic_energy_J, tensions_N, elongations_m, segment_temperatures_K) with its probes.
template <class Dyn>
TrajectoryRow trajectory_row_of(const Dyn& d, std::vector<Eigen::Vector3d> probes_W_m) {
  TrajectoryRow r;
  r.t_s = d.time_s();
  r.tip_W_m = d.tip_position_W_m();
  r.kinetic_energy_J = d.kinetic_energy_J();
  r.tensions_N = d.tensions_N();
  r.elongations_m = d.elongations_m();
  r.temperatures_K = d.segment_temperatures_K();
  r.probes_W_m = std::move(probes_W_m);
  return r;
}

/// The column names: t_s, tip_x_m, tip_y_m, tip_z_m, kinetic_energy_J, then per actuator
/// <name>_tension_N, <name>_elongation_m and <name>_temperature_degC (a segmented TCA: one
/// <name>_<k>_temperature_degC per segment, k = 0, 1, ... base to tip), then per probe
/// <name>_x_m, <name>_y_m, <name>_z_m; with `with_dt` (adaptive time steps) last dt_s.
std::vector<std::string> trajectory_columns(const RodModel& model, bool with_dt = false);

/// The header line (the column names, comma-separated).
void write_trajectory_header(std::ostream& os, const RodModel& model, bool with_dt = false);

/// The row's numbers in the order and units of the columns: temperatures in degC, nan for a
/// tension drive's temperature.
std::vector<double> trajectory_values(const TrajectoryRow& row);

/// One row of the CSV (t_s %.9g, positions and forces %.12e, energy %.9e, degC %.9f, dt_s
/// %.6e when set).
void write_trajectory_row(std::ostream& os, const TrajectoryRow& row);

/// How a run of the time loop ended.
struct TrajectoryOutcome {
  bool ok = false;           ///< the static state and every step converged
  long long steps_done = 0;  ///< converged (accepted) time steps
  /// Adaptive time steps: steps undone and retried smaller because their error estimate
  /// exceeded the tolerance, and because their Newton iteration failed.
  long long steps_rejected = 0;
  long long steps_failed = 0;
  std::string status = "converged";  ///< the failing solve's status (to_string of it)
  /// Why it stopped early (empty when ok): "static initial state did not converge (STATUS):
  /// ..." or "time step to t = T s failed (STATUS): ..."; the CSV's last line is "# " + it.
  std::string message;
};

}  // namespace tcasim::rod
