// Probes of the FE solution (docs/scenario-format.md "Probes and frames"): the element
// interpolation evaluated at the probe's s, exact for the discrete solution.
#include "rod/probes.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/internal/quadrature.hpp"
#include "common/so3.hpp"

namespace tcasim::beam_fe {

void Discretization::pose_at(const State& state, double s_m, Eigen::Vector3d& p_W_m,
                             Eigen::Matrix3d& R_WB) const {
  // A node: its own pose (the interpolation there equals it only to round-off).
  const int node = rod::sample_at(state.s_m, s_m);
  if (node >= 0) {
    p_W_m = state.p_W_m[static_cast<std::size_t>(node)];
    R_WB = state.q_WB[static_cast<std::size_t>(node)].toRotationMatrix();
    return;
  }
  // The element holding s: the last whose first node lies at or before s.
  int e = 0;
  while (e + 1 < elements_ && element_start_m(e + 1) <= s_m) ++e;
  const double xi = 2.0 * (s_m - element_start_m(e)) / element_length_m(e) - 1.0;
  double N[3], dN[3];
  internal::shape(order_, xi, N, dN);
  // The element's interpolation (beam_fe.hpp): p = sum_a N_a p_a; R = R_r exp(sum_a N_a psi_a)
  // with psi_a = log(R_r^T R_a), r the reference node (0 for order 1, the middle one for 2).
  const int first = e * order_;
  const int ref = order_ == 1 ? 0 : 1;
  const Eigen::Quaterniond q_ref = state.q_WB[static_cast<std::size_t>(first + ref)];
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), psi = Eigen::Vector3d::Zero();
  for (int a = 0; a <= order_; ++a) {
    const auto i = static_cast<std::size_t>(first + a);
    p += N[a] * state.p_W_m[i];
    if (a != ref) psi += N[a] * so3::log(q_ref.conjugate() * state.q_WB[i]);
  }
  p_W_m = p;
  R_WB = q_ref.toRotationMatrix() * so3::exp(psi);
}

std::vector<rod::ProbeResult> probe_results(const Discretization& disc, const State& state) {
  std::vector<rod::ProbeResult> out;
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  for (const rod::Probe& probe : disc.model().probes) {
    disc.pose_at(state, probe.s_m, p, R);
    out.push_back({probe.name, rod::probe_position_W_m(probe, p, R)});
  }
  return out;
}

}  // namespace tcasim::beam_fe
