// Scenario reader: the body (section, material, base rotation).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"
#include "rod/scenario_reading.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

// ---------------------------------------------------------------------------------------
// Body

/// Saint-Venant torsion constant of a w x h rectangle.
/// [TimoshenkoGoodier1970] Sec. 109 (torsion of a rectangular bar), with a >= b the sides:
///   J = a b^3/3 - (64 b^4/pi^5) sum_{n = 1, 3, 5, ...} tanh(n pi a/(2 b))/n^5.
/// The series is evaluated as sum 1/n^5 - sum (1 - tanh)/n^5: the first sum over odd n is
/// (1 - 2^-5) zeta(5) in closed form and the second decays like exp(-n pi), so the result
/// is exact to round-off after a handful of terms.
double rectangle_saint_venant_torsion(double w_m, double h_m) {
  constexpr double kZeta5 = 1.0369277551433699263;      // Riemann zeta(5)
  constexpr double kOddZeta5 = (31.0 / 32.0) * kZeta5;  // sum over odd n of 1/n^5
  constexpr int kMaxTerms = 200;
  const double a = std::max(w_m, h_m);
  const double b = std::min(w_m, h_m);
  double deficit = 0.0;  // sum (1 - tanh(x_n))/n^5
  for (int k = 0; k < kMaxTerms; ++k) {
    const double n = 2.0 * k + 1.0;
    const double x = n * units::kPi * a / (2.0 * b);
    const double e = std::exp(-2.0 * x);
    const double term = 2.0 * e / (1.0 + e) / std::pow(n, 5);  // 1 - tanh(x) = 2 e^-2x/(1 + e^-2x)
    deficit += term;
    if (term < std::numeric_limits<double>::epsilon() * 1e-3) break;
  }
  const double pi5 = std::pow(units::kPi, 5);
  return a * b * b * b / 3.0 - 64.0 * std::pow(b, 4) / pi5 * (kOddZeta5 - deficit);
}

}  // namespace

Section parse_section(const json& j, const std::string& path) {
  const std::string shape = peek_choice(j, path, "shape", {"circle", "rectangle", "custom"});
  Section s;
  bool torsion_allowed = true;
  std::vector<std::string> allowed{"shape", "torsion"};
  if (shape == "circle") {
    allowed.push_back("diameter_m");
  } else if (shape == "rectangle") {
    allowed.insert(allowed.end(), {"width_m", "height_m"});
  } else {
    allowed = {"shape", "area_m2", "I_x_m4", "I_y_m4", "J_m4"};
    torsion_allowed = false;
  }
  const Obj o(j, path, allowed);
  if (torsion_allowed && o.has("torsion")) {
    s.saint_venant_torsion = o.choice("torsion", {"polar", "saint-venant"}) == "saint-venant";
  }
  if (shape == "circle") {
    s.shape = Section::Shape::kCircle;
    const double d = o.positive("diameter_m");
    s.width_m = d;
    s.height_m = d;
    s.area_m2 = units::kPi * d * d / 4.0;
    s.I_x_m4 = units::kPi * std::pow(d, 4) / 64.0;
    s.I_y_m4 = s.I_x_m4;
    // For a circle the Saint-Venant constant equals the polar moment.
    s.J_m4 = s.I_x_m4 + s.I_y_m4;
  } else if (shape == "rectangle") {
    s.shape = Section::Shape::kRectangle;
    const double w = o.positive("width_m");
    const double h = o.positive("height_m");
    s.width_m = w;
    s.height_m = h;
    s.area_m2 = w * h;
    s.I_x_m4 = w * h * h * h / 12.0;  // int y^2 dA, y along height
    s.I_y_m4 = h * w * w * w / 12.0;  // int x^2 dA, x along width
    s.J_m4 = s.saint_venant_torsion ? rectangle_saint_venant_torsion(w, h) : s.I_x_m4 + s.I_y_m4;
  } else {
    s.shape = Section::Shape::kCustom;
    s.area_m2 = o.positive("area_m2");
    s.I_x_m4 = o.positive("I_x_m4");
    s.I_y_m4 = o.positive("I_y_m4");
    s.J_m4 = o.positive("J_m4");
  }
  return s;
}

BodyMaterial parse_body_material(const Obj& o) {
  BodyMaterial m;
  m.youngs_modulus_Pa = o.positive("youngs_modulus_Pa");
  m.poisson_ratio = o.number("poisson_ratio");
  // 0.5 (incompressible) is allowed: the paper uses it for EcoFlex.
  require(m.poisson_ratio >= 0.0 && m.poisson_ratio <= 0.5, o.key("poisson_ratio"), m.poisson_ratio,
          "must lie in [0, 0.5]");
  m.shear_modulus_Pa = m.youngs_modulus_Pa / (2.0 * (1.0 + m.poisson_ratio));
  if (const auto psi = o.optional_number("density_kg_m3")) {
    require(*psi >= 0.0, o.key("density_kg_m3"), *psi, "must not be negative");
    m.density_kg_m3 = *psi;
  }
  return m;
}

Eigen::Matrix3d parse_rotation(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  const std::string key = o.key(k);
  const std::string shape_rule = "must be a 3x3 array of numbers (row-major)";
  if (!v.is_array() || v.size() != 3) throw InputError(key, show(v), shape_rule);
  Eigen::Matrix3d R;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].is_array() || v[i].size() != 3) throw InputError(key, show(v), shape_rule);
    for (std::size_t c = 0; c < 3; ++c) {
      R(static_cast<int>(i), static_cast<int>(c)) =
          as_number(v[i][c], fmt::format("{}[{}][{}]", key, i, c));
    }
  }
  const double orth = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  require(orth <= kRotationTolerance, key, show(v),
          fmt::format("must be orthonormal: max |R^T R - I| = {} > {}", orth, kRotationTolerance));
  const double det = R.determinant();
  require(std::abs(det - 1.0) <= kRotationTolerance, key, show(v),
          fmt::format("must have determinant +1 (a rotation, not a reflection): det = {}", det));
  // Project onto SO(3) (nearest rotation, polar decomposition) so that the typed
  // round-off does not propagate.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

}  // namespace tcasim::rod::scenario_detail
