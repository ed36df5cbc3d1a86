#include "tca/curve.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim::tca {

std::vector<CurvePoint> elongation_curve(const Tca& tca, double tension_N,
                                         const std::vector<double>& temperatures_K) {
  std::vector<CurvePoint> curve;
  curve.reserve(temperatures_K.size());
  for (const double t_K : temperatures_K) {
    const ElongationState e = tca.elongation(tension_N, t_K);
    curve.push_back({t_K, e.elongation_m, tension_N, e.pitch_angle_rad, e.coils_closed});
  }
  return curve;
}

std::vector<double> temperature_grid(double lo, double hi, double step, const char* key) {
  require(step > 0.0, key, fmt::format("{}:{}:{}", lo, hi, step), "needs a step > 0");
  require(lo <= hi, key, fmt::format("{}:{}:{}", lo, hi, step), "needs start <= stop");
  // Tolerance for including the end point: decimal steps like 0.1 do not sum exactly.
  constexpr double kEndSlack = 1e-6;
  const auto count = static_cast<long>(std::floor((hi - lo) / step + kEndSlack));
  require(count < 1000000, key, fmt::format("{}:{}:{}", lo, hi, step),
          "gives more than a million temperatures");
  std::vector<double> grid;
  grid.reserve(static_cast<std::size_t>(count) + 1);
  for (long i = 0; i <= count; ++i) grid.push_back(lo + static_cast<double>(i) * step);
  return grid;
}

double hanging_load_tension_N(double mass_kg) {
  // A weight hung on the folded extension TCA (Fig. 4) pushes it shut: F = -m g.
  return -mass_kg * units::kStandardGravity_m_s2;
}

}  // namespace tcasim::tca
