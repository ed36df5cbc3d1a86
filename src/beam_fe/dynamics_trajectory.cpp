// The trajectory CSV of the FE dynamics (docs/scenario-format.md "Trajectory file").
#include <ostream>

#include "beam_fe/dynamics.hpp"
#include "rod/trajectory.hpp"

namespace tcasim::beam_fe {

rod::TrajectoryRow trajectory_row(const BeamDynamics& dyn) {
  rod::TrajectoryRow r;
  r.t_s = dyn.time_s();
  r.tip_W_m = dyn.tip_position_W_m();
  r.kinetic_energy_J = dyn.kinetic_energy_J();
  r.tensions_N = dyn.tensions_N();
  r.elongations_m = dyn.elongations_m();
  r.temperatures_K = dyn.segment_temperatures_K();
  for (const rod::ProbeResult& p : probe_results(dyn.discretization(), dyn.state()))
    r.probes_W_m.push_back(p.position_W_m);
  return r;
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
