// The trajectory row of the FE dynamics (docs/scenario-format.md "Trajectory file").
#include <utility>
#include <vector>

#include "beam_fe/dynamics.hpp"
#include "rod/trajectory.hpp"

namespace tcasim::beam_fe {

rod::TrajectoryRow trajectory_row(const BeamDynamics& dyn) {
  std::vector<Eigen::Vector3d> probes_W_m;
  for (const rod::ProbeResult& p : probe_results(dyn.discretization(), dyn.state()))
    probes_W_m.push_back(p.position_W_m);
  return rod::trajectory_row_of(dyn, std::move(probes_W_m));
}

}  // namespace tcasim::beam_fe
