// The trajectory CSV of the FE dynamics (docs/scenario-format.md "Trajectory file").
#include <ostream>
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

TrajectorySummary write_trajectory(BeamDynamics& dyn, const rod::RodModel& model,
                                   const LoadsAt& loads_at, long long steps, long long output_every,
                                   std::ostream& os,
                                   const std::function<void(const BeamDynamics&)>& after_row) {
  rod::write_trajectory_header(os, model);
  const rod::TrajectoryOutcome o = rod::run_trajectory(
      dyn, loads_at, dyn.time_step_s(), steps, output_every, trajectory_row,
      [&](const rod::TrajectoryRow& row) {
        rod::write_trajectory_row(os, row);
        if (after_row) after_row(dyn);
      });
  if (!o.ok) os << "# " << o.message << '\n';
  return TrajectorySummary{o.ok, o.steps_done, o.message};
}

}  // namespace tcasim::beam_fe
