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
#include "rod/internal/scenario_reading.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"

namespace tcasim::rod::scenario_detail {
Section parse_section(const json& j, const std::string& path, double length_m) {
  const std::string shape = peek_choice(j, path, "shape", {"circle", "rectangle", "custom"});
  Section s;
  bool torsion_allowed = true;
  std::vector<std::string> allowed{"shape", "torsion"};
  if (shape == "circle") {
    allowed.push_back("diameter_m");
  } else if (shape == "rectangle") {
    allowed.insert(allowed.end(), {"width_m", "height_m"});
  } else {
    allowed = {"shape", "area_m2", "I_x_m4", "I_y_m4", "J_m4", "contact_radius_m"};
    torsion_allowed = false;
  }
  const Obj o(j, path, allowed);
  if (torsion_allowed && o.has("torsion")) {
    s.saint_venant_torsion = o.choice("torsion", {"polar", "saint-venant"}) == "saint-venant";
  }
  // Each dimension is a number or a profile along s (docs/scenario-format.md "Profiles along
  // the body"); the derived properties follow pointwise (Section::properties_at).
  const auto positive = [&](const std::string& k) {
    return parse_profile_key(o, k, length_m, ValueRule::kPositive);
  };
  if (shape == "circle") {
    s.shape = Section::Shape::kCircle;
    s.width_profile = positive("diameter_m");
    s.height_profile = s.width_profile;
  } else if (shape == "rectangle") {
    s.shape = Section::Shape::kRectangle;
    s.width_profile = positive("width_m");
    s.height_profile = positive("height_m");
  } else {
    s.shape = Section::Shape::kCustom;
    s.area_profile = positive("area_m2");
    s.I_x_profile = positive("I_x_m4");
    s.I_y_profile = positive("I_y_m4");
    s.J_profile = positive("J_m4");
    if (o.has("contact_radius_m")) s.contact_radius_m = o.positive("contact_radius_m");
  }
  return s;
}

BodyMaterial parse_body_material(const Obj& o, double length_m) {
  BodyMaterial m;
  m.youngs_modulus_profile =
      parse_profile_key(o, "youngs_modulus_Pa", length_m, ValueRule::kPositive);
  m.poisson_ratio = o.number("poisson_ratio");
  // 0.5 (incompressible) is allowed: the paper uses it for EcoFlex. The file gives no shear
  // modulus: G = E / (2 (1 + nu)) at each s (BodyMaterial::shear_modulus).
  require(m.poisson_ratio >= 0.0 && m.poisson_ratio <= 0.5, o.key("poisson_ratio"), m.poisson_ratio,
          "must lie in [0, 0.5]");
  if (o.has("density_kg_m3")) {
    m.density_profile = parse_profile_key(o, "density_kg_m3", length_m, ValueRule::kNonNegative);
  }
  if (o.has("viscosity_Pa_s")) {
    m.viscosity_profile = parse_profile_key(o, "viscosity_Pa_s", length_m, ValueRule::kNonNegative);
  }
  return m;
}

/// body.reference_curvature_1_m: three components, each a number or a profile.
std::array<Profile, 3> parse_reference_curvature(const Obj& o, const std::string& k,
                                                 double length_m) {
  const json& v = o.required(k);
  if (!v.is_array() || v.size() != 3) {
    throw InputError(o.key(k), show(v),
                     "must be an array of 3 components, each a number or a profile");
  }
  std::array<Profile, 3> out;
  for (std::size_t i = 0; i < 3; ++i) {
    out[i] = parse_profile(v[i], fmt::format("{}[{}]", o.key(k), i), length_m, ValueRule::kAny);
  }
  return out;
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
