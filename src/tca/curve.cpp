#include "tca/curve.hpp"

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

double hanging_load_tension_N(double mass_kg) {
  // A weight hung on the folded extension TCA (Fig. 4) pushes it shut: F = -m g.
  return -mass_kg * units::kStandardGravity_m_s2;
}

}  // namespace tcasim::tca
