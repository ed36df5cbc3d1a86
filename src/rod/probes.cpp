#include "rod/probes.hpp"

#include <cmath>
#include <stdexcept>

namespace tcasim::rod {
namespace {

/// A sample within this fraction of the sampled length of s is the sample at s: far below any
/// step, far above the round-off of s_i = i h.
constexpr double kSampleMatchRelative = 1e-12;

}  // namespace

Eigen::Vector3d probe_position_W_m(const Probe& probe, const Eigen::Vector3d& p_W_m,
                                   const Eigen::Matrix3d& R_WB) {
  return p_W_m + R_WB * probe.offset_B_m;
}

int sample_at(const std::vector<double>& s_m, double s) {
  if (s_m.empty()) return -1;
  const double match = kSampleMatchRelative * std::abs(s_m.back() - s_m.front());
  for (std::size_t i = 0; i < s_m.size(); ++i) {
    if (std::abs(s_m[i] - s) <= match) return static_cast<int>(i);
  }
  return -1;
}

std::vector<Eigen::Vector3d> probe_positions_at_samples(const RodModel& model,
                                                        const std::vector<double>& s_m,
                                                        const std::vector<Eigen::Vector3d>& p_W_m,
                                                        const std::vector<Eigen::Matrix3d>& R_WB) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(model.probes.size());
  for (const Probe& probe : model.probes) {
    const int i = sample_at(s_m, probe.s_m);
    if (i < 0) throw std::logic_error("probe '" + probe.name + "' is not at a sample of the grid");
    out.push_back(probe_position_W_m(probe, p_W_m[static_cast<std::size_t>(i)],
                                     R_WB[static_cast<std::size_t>(i)]));
  }
  return out;
}

}  // namespace tcasim::rod
