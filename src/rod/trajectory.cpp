#include "rod/trajectory.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/units.hpp"

namespace tcasim::rod {

std::vector<std::string> trajectory_columns(const RodModel& model, bool with_dt) {
  std::vector<std::string> c = {"t_s", "tip_x_m", "tip_y_m", "tip_z_m", "kinetic_energy_J"};
  for (const auto& a : model.actuators) {
    c.push_back(a.name + "_tension_N");
    c.push_back(a.name + "_elongation_m");
    if (a.drive.type == Drive::Type::kTca && a.drive.segmented) {
      for (std::size_t k = 0; k < a.drive.segments.size(); ++k) {
        c.push_back(fmt::format("{}_{}_temperature_degC", a.name, k));
      }
    } else {
      c.push_back(a.name + "_temperature_degC");
    }
  }
  for (const auto& p : model.probes) {
    for (const char* axis : {"_x_m", "_y_m", "_z_m"}) c.push_back(p.name + axis);
  }
  if (with_dt) c.push_back("dt_s");
  return c;
}

void write_trajectory_header(std::ostream& os, const RodModel& model, bool with_dt) {
  const std::vector<std::string> columns = trajectory_columns(model, with_dt);
  for (std::size_t i = 0; i < columns.size(); ++i) os << (i > 0 ? "," : "") << columns[i];
  os << '\n';
}

std::vector<double> trajectory_values(const TrajectoryRow& row) {
  std::vector<double> v = {row.t_s, row.tip_W_m.x(), row.tip_W_m.y(), row.tip_W_m.z(),
                           row.kinetic_energy_J};
  for (std::size_t i = 0; i < row.tensions_N.size(); ++i) {
    v.push_back(row.tensions_N[i]);
    v.push_back(row.elongations_m[i]);
    if (i >= row.temperatures_K.size() || row.temperatures_K[i].empty()) {
      v.push_back(std::nan(""));  // tension drive: no temperature
      continue;
    }
    for (const double T_K : row.temperatures_K[i]) v.push_back(units::K_to_degC(T_K));
  }
  for (const Eigen::Vector3d& p : row.probes_W_m) v.insert(v.end(), {p.x(), p.y(), p.z()});
  if (row.dt_s) v.push_back(*row.dt_s);
  return v;
}

void write_trajectory_row(std::ostream& os, const TrajectoryRow& row) {
  os << fmt::format("{:.9g},{:.12e},{:.12e},{:.12e},{:.9e}", row.t_s, row.tip_W_m.x(),
                    row.tip_W_m.y(), row.tip_W_m.z(), row.kinetic_energy_J);
  for (std::size_t i = 0; i < row.tensions_N.size(); ++i) {
    os << fmt::format(",{:.12e},{:.12e}", row.tensions_N[i], row.elongations_m[i]);
    if (i >= row.temperatures_K.size() || row.temperatures_K[i].empty()) {
      os << ",nan";  // tension drive: no temperature
      continue;
    }
    for (const double T_K : row.temperatures_K[i]) {
      os << fmt::format(",{:.9f}", units::K_to_degC(T_K));
    }
  }
  for (const Eigen::Vector3d& p : row.probes_W_m)
    os << fmt::format(",{:.12e},{:.12e},{:.12e}", p.x(), p.y(), p.z());
  if (row.dt_s) os << fmt::format(",{:.6e}", *row.dt_s);
  os << '\n';
}

}  // namespace tcasim::rod
