#pragma once
/// Elongation-temperature curves of one TCA under a constant load: the computation shared
/// by `tcasim tca` and the Fig. 5 validation, so both report the same numbers.
#include <optional>
#include <vector>

#include "tca/tca.hpp"

namespace tcasim::tca {

/// One point of an elongation-temperature curve.
struct CurvePoint {
  double temperature_K;
  double elongation_m;     ///< delta (0 while the coils of an extension TCA are closed)
  double tension_N;        ///< the applied tension F (constant along the curve)
  double pitch_angle_rad;  ///< alpha, Eq. (5)
  bool coils_closed;
};

/// Elongation under constant tension F at each temperature, in order.
std::vector<CurvePoint> elongation_curve(const Tca& tca, double tension_N,
                                         const std::vector<double>& temperatures_K);

/// The tension of a hanging mass m [kg] on a TCA that it compresses: F = -m g.
double hanging_load_tension_N(double mass_kg);

}  // namespace tcasim::tca
