#include "rod/model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim::rod {

double Section::half_extent_m(double dir_x, double dir_y) const {
  const double norm = std::hypot(dir_x, dir_y);
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    throw DomainError("Section::half_extent_m: direction (" + format_value(dir_x) + ", " +
                      format_value(dir_y) + ") must be a finite non-zero vector");
  }
  const double c = std::abs(dir_x) / norm;
  const double s = std::abs(dir_y) / norm;
  switch (shape) {
    case Shape::kCircle:
      return 0.5 * width_m;
    case Shape::kRectangle: {
      // The ray t (c, s) leaves the rectangle |x| <= w/2, |y| <= h/2 at the first edge it
      // meets; a zero component never limits it.
      const double tx = c > 0.0 ? 0.5 * width_m / c : HUGE_VAL;
      const double ty = s > 0.0 ? 0.5 * height_m / s : HUGE_VAL;
      return std::min(tx, ty);
    }
    case Shape::kCustom:
      break;
  }
  // A custom section gives only A, I_x, I_y and J: there is no edge to measure to.
  throw DomainError(
      "Section::half_extent_m: a custom section (area_m2, I_x_m4, I_y_m4, J_m4) has no "
      "outline, so its half extent is undefined");
}

namespace {
// Angle of the helix offset at s: theta(s) = phase + 2 pi k s.
double helix_angle(const Routing& r, double s_m) {
  return r.phase_rad + 2.0 * units::kPi * r.turns_per_m * s_m;
}
}  // namespace

Eigen::Vector3d Routing::r(double s_m) const {
  if (type == Type::kStraight) return {offset_m.x(), offset_m.y(), 0.0};
  // r(s) = R (cos theta, sin theta, 0)
  const double theta = helix_angle(*this, s_m);
  return {radius_m * std::cos(theta), radius_m * std::sin(theta), 0.0};
}

Eigen::Vector3d Routing::dr(double s_m) const {
  if (type == Type::kStraight) return Eigen::Vector3d::Zero();
  // r'(s) = R w (-sin theta, cos theta, 0), w = 2 pi k
  const double w = 2.0 * units::kPi * turns_per_m;
  const double theta = helix_angle(*this, s_m);
  return {-radius_m * w * std::sin(theta), radius_m * w * std::cos(theta), 0.0};
}

Eigen::Vector3d Routing::ddr(double s_m) const {
  if (type == Type::kStraight) return Eigen::Vector3d::Zero();
  // r''(s) = -R w^2 (cos theta, sin theta, 0)
  const double w = 2.0 * units::kPi * turns_per_m;
  const double theta = helix_angle(*this, s_m);
  return {-radius_m * w * w * std::cos(theta), -radius_m * w * w * std::sin(theta), 0.0};
}

Eigen::Vector3d RodModel::shear_extension_stiffness() const {
  // [Pawlowski2019] text below Eq. (12): K_nu = diag(G A, G A, E A) (no shear correction factor).
  const double GA = material.shear_modulus_Pa * section.area_m2;
  const double EA = material.youngs_modulus_Pa * section.area_m2;
  return {GA, GA, EA};
}

Eigen::Vector3d RodModel::bending_torsion_stiffness() const {
  // [Pawlowski2019] text below Eq. (12): K_omega = diag(E I_x, E I_y, G J).
  const double E = material.youngs_modulus_Pa;
  return {E * section.I_x_m4, E * section.I_y_m4, material.shear_modulus_Pa * section.J_m4};
}

Eigen::Vector3d RodModel::weight_per_length_W_N_m() const {
  // [Pawlowski2019] Eq. (14), corrected (docs/conventions.md): psi A g in the world frame.
  return material.density_kg_m3 * section.area_m2 * gravity_W_m_s2;
}

RodModel with_tca_material(const RodModel& model, const tca::Material& material,
                           std::optional<tca::F12Form> f12_form) {
  RodModel m = model;
  for (auto& [id, t] : m.tcas) {
    tca::Parameters p = t->parameters();
    if (f12_form) p.f12_form = *f12_form;
    t = std::make_shared<const tca::Tca>(p, material);
  }
  for (auto& a : m.actuators) {
    if (a.drive.type == Drive::Type::kTca) a.drive.tca = m.tcas.at(a.drive.tca_id);
  }
  return m;
}

}  // namespace tcasim::rod
