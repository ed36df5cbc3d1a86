// The trajectory CSV of the FE dynamics (docs/scenario-format.md "Trajectory file").
#include <fmt/format.h>

#include <ostream>

#include "beam_fe/dynamics.hpp"
#include "rod/trajectory.hpp"

namespace tcasim::beam_fe {

TrajectorySummary write_trajectory(BeamDynamics& dyn, const rod::RodModel& model,
                                   const LoadsAt& loads_at, long long steps, long long output_every,
                                   std::ostream& os,
                                   const std::function<void(const BeamDynamics&)>& after_row) {
  TrajectorySummary out;
  rod::write_trajectory_header(os, model);
  auto write_row = [&] {
    std::vector<Eigen::Vector3d> probes_W_m;
    for (const rod::ProbeResult& p : probe_results(dyn.discretization(), dyn.state()))
      probes_W_m.push_back(p.position_W_m);
    rod::write_trajectory_row(os, dyn.time_s(), dyn.tip_position_W_m(), dyn.kinetic_energy_J(),
                              dyn.tensions_N(), dyn.elongations_m(), dyn.segment_temperatures_K(),
                              probes_W_m);
    if (after_row) after_row(dyn);
  };
  const BeamDynamicsSummary init = dyn.initialize(loads_at(0.0));
  if (!init.converged()) {
    out.message = fmt::format("static initial state did not converge ({}): {}",
                              to_string(init.status), init.message);
    os << "# " << out.message << '\n';
    return out;
  }
  write_row();
  const double dt = dyn.time_step_s();
  for (long long k = 1; k <= steps; ++k) {
    const double t_new = k * dt;
    const BeamDynamicsSummary s = dyn.step(loads_at(t_new));
    if (!s.converged()) {
      out.message = fmt::format("time step to t = {:.9g} s failed ({}): {}", t_new,
                                to_string(s.status), s.message);
      os << "# " << out.message << '\n';
      return out;
    }
    out.steps_done = k;
    if (k % output_every == 0 || k == steps) write_row();
  }
  out.ok = true;
  return out;
}

}  // namespace tcasim::beam_fe
