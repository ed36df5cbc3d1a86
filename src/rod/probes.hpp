#pragma once
/// Body-fixed probes (docs/scenario-format.md "Probes and frames"): the world position of a
/// point given in the body frame at its arc length, shared by both solvers and their dynamics.
#include <Eigen/Core>
#include <vector>

#include "rod/model.hpp"

namespace tcasim::rod {

/// World position of `probe` on the centerline pose (p_W_m, R_WB) at probe.s_m [m]:
/// p_W + R_WB offset_B.
Eigen::Vector3d probe_position_W_m(const Probe& probe, const Eigen::Vector3d& p_W_m,
                                   const Eigen::Matrix3d& R_WB);

/// The index of the sample of `s_m` (increasing) at s (within 1e-12 of the sampled length), or
/// -1 when none lies there.
int sample_at(const std::vector<double>& s_m, double s);

/// Positions of every probe of `model` from samples of the centerline that include each
/// probe's s (sample_at): a grid with a node at every probe. Throws std::logic_error when a
/// probe's s is not a sample (the caller built the grid without it).
std::vector<Eigen::Vector3d> probe_positions_at_samples(const RodModel& model,
                                                        const std::vector<double>& s_m,
                                                        const std::vector<Eigen::Vector3d>& p_W_m,
                                                        const std::vector<Eigen::Matrix3d>& R_WB);

}  // namespace tcasim::rod
