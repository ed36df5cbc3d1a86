#pragma once
/// Bodies whose section varies along s (docs/scenario-format.md "Profiles along the body"),
/// built from scenario documents, with the closed forms both solvers are tested against.
///
/// A cantilever along +z under an end moment M about world x carries n = 0 and m_B = M e_x
/// at every s (R = Rot_x(theta) leaves e_x fixed), so its curvature is kappa(s) = M / (E I(s))
/// and p(L) = int_0^L (0, -sin theta, cos theta) ds with theta(s) = int_0^s kappa.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/units.hpp"

namespace tcasim::test_support {

/// p(L) = int_0^L (0, -sin theta, cos theta) ds by 16-point Gauss-Legendre on 64 panels per
/// piece between the knots (theta smooth on each: converged to round-off).
inline Eigen::Vector3d planar_tip_position(const std::function<double(double)>& theta,
                                           const std::vector<double>& knots) {
  static const std::array<double, 8> x{0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                                       0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                                       0.9445750230732326, 0.9894009349916499};
  static const std::array<double, 8> w{0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                       0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                       0.0622535239386479, 0.0271524594117541};
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  constexpr int kPanels = 64;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double h = (knots[k + 1] - knots[k]) / kPanels;
    for (int i = 0; i < kPanels; ++i) {
      const double mid = knots[k] + (i + 0.5) * h;
      for (std::size_t g = 0; g < x.size(); ++g) {
        for (const double sign : {-1.0, 1.0}) {
          const double t = theta(mid + sign * 0.5 * h * x[g]);
          p += 0.5 * h * w[g] * Eigen::Vector3d(0.0, -std::sin(t), std::cos(t));
        }
      }
    }
  }
  return p;
}

/// The end-moment cantilevers: L, E, the two diameters and M (theta(L) about 1 rad).
struct MomentCantilever {
  double length_m = 0.1;
  double E_Pa = 1.0e6;
  double d0_m = 0.010;  ///< diameter at the base
  double d1_m = 0.005;  ///< diameter at the tip (tapered) or beyond the step
  double step_s_m = 0.04;
  double moment_Nm = 1.0e-3;

  /// theta(s) of the linear taper d(s) = d0 + (d1 - d0) s / L: with I = pi d^4 / 64,
  /// int_0^s d(t)^-4 dt = (d0^-3 - d(s)^-3) / (3 a), a = (d1 - d0) / L.
  double tapered_theta(double s) const {
    const double a = (d1_m - d0_m) / length_m;
    const double d = d0_m + a * s;
    return 64.0 * moment_Nm / (units::kPi * E_Pa) * (std::pow(d0_m, -3) - std::pow(d, -3)) /
           (3.0 * a);
  }
  /// theta(s) of the stepped section (d0 before step_s_m, d1 after): piecewise linear.
  double stepped_theta(double s) const {
    const double k0 = 64.0 * moment_Nm / (units::kPi * E_Pa * std::pow(d0_m, 4));
    const double k1 = 64.0 * moment_Nm / (units::kPi * E_Pa * std::pow(d1_m, 4));
    return s <= step_s_m ? k0 * s : k0 * step_s_m + k1 * (s - step_s_m);
  }

  /// The scenario: a circle whose diameter is the profile (s_m, values), the end moment.
  nlohmann::json scenario(const std::vector<double>& s_m, const std::vector<double>& d_m) const {
    nlohmann::json j;
    j["schema"] = "tcasim.scenario/1";
    j["name"] = "moment-cantilever";
    j["body"]["length_m"] = length_m;
    j["body"]["section"] = {{"shape", "circle"}, {"diameter_m", {{"s_m", s_m}, {"values", d_m}}}};
    j["body"]["material"] = {{"youngs_modulus_Pa", E_Pa}, {"poisson_ratio", 0.5}};
    j["tip_load"]["moment_Nm"] = {moment_Nm, 0.0, 0.0};
    return j;
  }
  nlohmann::json tapered() const { return scenario({0.0, length_m}, {d0_m, d1_m}); }
  nlohmann::json stepped() const {
    return scenario({0.0, step_s_m, step_s_m, length_m}, {d0_m, d0_m, d1_m, d1_m});
  }

  /// The closed-form tip positions p(L) of tapered() and stepped().
  Eigen::Vector3d tapered_tip() const {
    return planar_tip_position([this](double s) { return tapered_theta(s); }, {0.0, length_m});
  }
  Eigen::Vector3d stepped_tip() const {
    return planar_tip_position([this](double s) { return stepped_theta(s); },
                               {0.0, step_s_m, length_m});
  }
};

/// The loaded varying body both solvers' tests use (without strings, gravity or density):
/// stepped and tapered (diameter 10, 9 | 7, 6 mm with a jump at 30 mm), precurved about body
/// y (0 -> 1 1/m over 60 mm, a jump to 2 1/m there), under the tip moment (2e-4, -1e-4, 0) N m.
inline nlohmann::json loaded_varying_body() {
  const MomentCantilever c;
  nlohmann::json j = c.scenario({0.0, 0.03, 0.03, c.length_m}, {0.010, 0.009, 0.007, 0.006});
  j["body"]["reference_curvature_1_m"] = {
      0.0, nlohmann::json{{"s_m", {0.0, 0.06, 0.06, c.length_m}}, {"values", {0.0, 1.0, 2.0, 2.0}}},
      0.0};
  j["tip_load"]["moment_Nm"] = {2e-4, -1e-4, 0.0};
  return j;
}

/// The soft tentacle hanging under gravity of the varying-body benchmark and its tests: 0.2 m
/// of EcoFlex (E 69 kPa, density 1070), two tendons 3 mm off-axis (0.05 and 0.02 N); uniform
/// (diameter 15 mm) or tapered (20 to 10 mm) with a jump of the reference curvature at L/2.
inline nlohmann::json hanging_tentacle(bool tapered) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "tentacle",
    "body": {"length_m": 0.2, "section": {"shape": "circle", "diameter_m": 0.015},
             "material": {"youngs_modulus_Pa": 69e3, "poisson_ratio": 0.5,
                          "density_kg_m3": 1070}},
    "base": {"rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]]},
    "gravity_m_s2": [0, 0, -9.80665],
    "actuators": [
      {"name": "tendon-x", "routing": {"type": "straight", "offset_m": [0.003, 0.0]},
       "drive": {"type": "tension", "tension_N": 0.05}},
      {"name": "tendon-y", "routing": {"type": "straight", "offset_m": [0.0, 0.003]},
       "drive": {"type": "tension", "tension_N": 0.02}}]})");
  if (tapered) {
    j["body"]["section"]["diameter_m"] = {{"s_m", {0.0, 0.2}}, {"values", {0.020, 0.010}}};
    j["body"]["reference_curvature_1_m"] = {
        nlohmann::json{{"s_m", {0.0, 0.1, 0.1, 0.2}}, {"values", {0.0, 0.0, -2.0, -2.0}}}, 0.0,
        0.0};
  }
  return j;
}

}  // namespace tcasim::test_support
