// The trajectory CSV of the FE dynamics (docs/scenario-format.md "Trajectory file").
#include <fmt/format.h>

#include <ostream>

#include "beam_fe/dynamics.hpp"

namespace tcasim::beam_fe {

TrajectorySummary write_trajectory(BeamDynamics& dyn, const rod::RodModel& model,
                                   const LoadsAt& loads_at, long long steps, long long output_every,
                                   std::ostream& os,
                                   const std::function<void(const BeamDynamics&)>& after_row) {
  TrajectorySummary out;
  os << "t_s,tip_x_m,tip_y_m,tip_z_m,kinetic_energy_J";
  for (const auto& a : model.actuators) {
    os << ',' << a.name << "_tension_N," << a.name << "_elongation_m," << a.name
       << "_temperature_degC";
  }
  os << '\n';
  auto write_row = [&] {
    const Eigen::Vector3d p = dyn.tip_position_W_m();
    os << fmt::format("{:.9g},{:.12e},{:.12e},{:.12e},{:.9e}", dyn.time_s(), p.x(), p.y(), p.z(),
                      dyn.kinetic_energy_J());
    const std::vector<double> t = dyn.tensions_N(), e = dyn.elongations_m();
    for (std::size_t i = 0; i < t.size(); ++i) {
      os << fmt::format(",{:.12e},{:.12e},nan", t[i], e[i]);  // tension drives: no temperature
    }
    os << '\n';
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
