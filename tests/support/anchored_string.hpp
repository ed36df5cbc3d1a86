#pragma once
/// A straight string anchored inside the body (docs/scenario-format.md "String extent"), and
/// its closed form, which both solvers are tested against.
///
/// A straight, uniform cantilever along +z, no gravity, no tip load, one straight string at
/// body offset (x, 0, 0) with tension T over the span [s_a, s_b]. Outside the span no string
/// crosses the section and nothing else loads it: the rod keeps its reference strains there
/// (straight). Inside, the total section wrench, rod plus string, is zero:
///   K_nu (nu - e3) + T qh = 0,  K_omega omega + T r x qh = 0,
/// solved exactly by nu = (1 - T / EA) e3, omega = (0, T x / EI_y, 0), for which
/// q = nu + omega x r = (nu_z - omega_y x) e3, so qh = e3: a constant-curvature arc.
#include <Eigen/Core>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common/units.hpp"

namespace tcasim::test_support {

struct AnchoredString {
  double length_m = 0.1;
  double E_Pa = 1.0e6;
  double diameter_m = 0.010;
  double offset_m = 0.003;  ///< x offset of the string
  double tension_N = 1.5;   ///< curvature about 9 1/m on the span
  double s_a_m = 0.0;
  double s_b_m = 0.06;

  double EA() const { return E_Pa * units::kPi * diameter_m * diameter_m / 4.0; }
  double EI() const { return E_Pa * units::kPi * std::pow(diameter_m, 4) / 64.0; }
  double nu_z() const { return 1.0 - tension_N / EA(); }
  double kappa() const { return tension_N * offset_m / EI(); }  ///< omega_y on the span

  /// Tip position: straight to s_a, the arc p' = R nu with R = Rot_y(kappa (s - s_a)) to s_b,
  /// straight along the last tangent to L.
  Eigen::Vector3d tip_position() const {
    const double k = kappa(), th = k * (s_b_m - s_a_m);
    Eigen::Vector3d p(0.0, 0.0, s_a_m);
    p += nu_z() * Eigen::Vector3d((1.0 - std::cos(th)) / k, 0.0, std::sin(th) / k);
    p += (length_m - s_b_m) * Eigen::Vector3d(std::sin(th), 0.0, std::cos(th));
    return p;
  }
  /// Tip rotation angle about body y.
  double tip_angle() const { return kappa() * (s_b_m - s_a_m); }
  /// The string's elongation: (s_b - s_a) (|q| - 1).
  double elongation_m() const { return (s_b_m - s_a_m) * (nu_z() - kappa() * offset_m - 1.0); }

  nlohmann::json scenario() const {
    nlohmann::json j;
    j["schema"] = "tcasim.scenario/1";
    j["name"] = "anchored-string";
    j["body"]["length_m"] = length_m;
    j["body"]["section"] = {{"shape", "circle"}, {"diameter_m", diameter_m}};
    j["body"]["material"] = {{"youngs_modulus_Pa", E_Pa}, {"poisson_ratio", 0.5}};
    j["actuators"] = nlohmann::json::array();
    j["actuators"].push_back({{"name", "s"},
                              {"routing", {{"type", "straight"}, {"offset_m", {offset_m, 0.0}}}},
                              {"span_m", {s_a_m, s_b_m}},
                              {"drive", {{"type", "tension"}, {"tension_N", tension_N}}}});
    return j;
  }
};

}  // namespace tcasim::test_support
