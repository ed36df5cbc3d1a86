#include "rod/trajectory.hpp"

#include <fmt/format.h>

#include "common/units.hpp"

namespace tcasim::rod {

void write_trajectory_header(std::ostream& os, const RodModel& model) {
  os << "t_s,tip_x_m,tip_y_m,tip_z_m,kinetic_energy_J";
  for (const auto& a : model.actuators) {
    os << ',' << a.name << "_tension_N," << a.name << "_elongation_m";
    if (a.drive.type == Drive::Type::kTca && a.drive.segmented) {
      for (std::size_t k = 0; k < a.drive.segments.size(); ++k) {
        os << ',' << a.name << '_' << k << "_temperature_degC";
      }
    } else {
      os << ',' << a.name << "_temperature_degC";
    }
  }
  for (const auto& p : model.probes) os << fmt::format(",{0}_x_m,{0}_y_m,{0}_z_m", p.name);
  os << '\n';
}

void write_trajectory_row(std::ostream& os, double t_s, const Eigen::Vector3d& tip_W_m,
                          double kinetic_energy_J, const std::vector<double>& tensions_N,
                          const std::vector<double>& elongations_m,
                          const std::vector<std::vector<double>>& temperatures_K,
                          const std::vector<Eigen::Vector3d>& probes_W_m) {
  os << fmt::format("{:.9g},{:.12e},{:.12e},{:.12e},{:.9e}", t_s, tip_W_m.x(), tip_W_m.y(),
                    tip_W_m.z(), kinetic_energy_J);
  for (std::size_t i = 0; i < tensions_N.size(); ++i) {
    os << fmt::format(",{:.12e},{:.12e}", tensions_N[i], elongations_m[i]);
    if (i >= temperatures_K.size() || temperatures_K[i].empty()) {
      os << ",nan";  // tension drive: no temperature
      continue;
    }
    for (const double T_K : temperatures_K[i]) os << fmt::format(",{:.9f}", units::K_to_degC(T_K));
  }
  for (const Eigen::Vector3d& p : probes_W_m)
    os << fmt::format(",{:.12e},{:.12e},{:.12e}", p.x(), p.y(), p.z());
  os << '\n';
}

}  // namespace tcasim::rod
