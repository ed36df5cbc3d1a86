#pragma once
/// The trajectory CSV of `tcasim simulate` (docs/scenario-format.md "Trajectory file"): one
/// header and one row format for both methods' dynamics.
#include <Eigen/Core>
#include <ostream>
#include <vector>

#include "rod/model.hpp"

namespace tcasim::rod {

/// The header line: t_s, tip_x_m, tip_y_m, tip_z_m, kinetic_energy_J, then per actuator
/// <name>_tension_N, <name>_elongation_m and <name>_temperature_degC (a segmented TCA: one
/// <name>_<k>_temperature_degC per segment, k = 0, 1, ... base to tip), then per probe
/// <name>_x_m, <name>_y_m, <name>_z_m.
void write_trajectory_header(std::ostream& os, const RodModel& model);

/// One row at time t_s [s]: the tip position [m], the kinetic energy [J] and per actuator the
/// tension of one string [N], its elongation [m] and its temperatures [K] (written in degC;
/// none: a tension drive, written as nan). temperatures_K may be empty (no actuator has any).
/// probes_W_m: the world position of each probe of the model [m], in the model's order.
void write_trajectory_row(std::ostream& os, double t_s, const Eigen::Vector3d& tip_W_m,
                          double kinetic_energy_J, const std::vector<double>& tensions_N,
                          const std::vector<double>& elongations_m,
                          const std::vector<std::vector<double>>& temperatures_K,
                          const std::vector<Eigen::Vector3d>& probes_W_m);

}  // namespace tcasim::rod
