#include "rod/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim::rod {

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

SectionProperties Section::properties_at(double s, Side side) const {
  SectionProperties p;
  switch (shape) {
    case Shape::kCircle: {
      const double d = width_profile.value(s, side);
      p.width_m = d;
      p.height_m = d;
      p.area_m2 = units::kPi * d * d / 4.0;
      p.I_x_m4 = units::kPi * std::pow(d, 4) / 64.0;
      p.I_y_m4 = p.I_x_m4;
      // For a circle the Saint-Venant constant equals the polar moment.
      p.J_m4 = p.I_x_m4 + p.I_y_m4;
      break;
    }
    case Shape::kRectangle: {
      const double w = width_profile.value(s, side);
      const double h = height_profile.value(s, side);
      p.width_m = w;
      p.height_m = h;
      p.area_m2 = w * h;
      p.I_x_m4 = w * h * h * h / 12.0;  // int y^2 dA, y along height
      p.I_y_m4 = h * w * w * w / 12.0;  // int x^2 dA, x along width
      p.J_m4 = saint_venant_torsion ? rectangle_saint_venant_torsion(w, h) : p.I_x_m4 + p.I_y_m4;
      break;
    }
    case Shape::kCustom:
      p.area_m2 = area_profile.value(s, side);
      p.I_x_m4 = I_x_profile.value(s, side);
      p.I_y_m4 = I_y_profile.value(s, side);
      p.J_m4 = J_profile.value(s, side);
      break;
  }
  return p;
}

SectionProperties Section::derivatives_at(double s, Side side) const {
  SectionProperties d;
  switch (shape) {
    case Shape::kCircle: {
      const double D = width_profile.value(s, side);
      const double dD = width_profile.slope(s, side);
      d.width_m = dD;
      d.height_m = dD;
      d.area_m2 = units::kPi * D * dD / 2.0;
      d.I_x_m4 = units::kPi * D * D * D * dD / 16.0;
      d.I_y_m4 = d.I_x_m4;
      d.J_m4 = 2.0 * d.I_x_m4;
      break;
    }
    case Shape::kRectangle: {
      const double w = width_profile.value(s, side), h = height_profile.value(s, side);
      const double dw = width_profile.slope(s, side), dh = height_profile.slope(s, side);
      d.width_m = dw;
      d.height_m = dh;
      d.area_m2 = dw * h + w * dh;
      d.I_x_m4 = (dw * h * h * h + 3.0 * w * h * h * dh) / 12.0;
      d.I_y_m4 = (dh * w * w * w + 3.0 * h * w * w * dw) / 12.0;
      if (saint_venant_torsion) {
        // Central differences of the series (smooth in w and h): relative error ~1e-10.
        const double ew = 1e-5 * w, eh = 1e-5 * h;
        const double Jw = (rectangle_saint_venant_torsion(w + ew, h) -
                           rectangle_saint_venant_torsion(w - ew, h)) /
                          (2.0 * ew);
        const double Jh = (rectangle_saint_venant_torsion(w, h + eh) -
                           rectangle_saint_venant_torsion(w, h - eh)) /
                          (2.0 * eh);
        d.J_m4 = Jw * dw + Jh * dh;
      } else {
        d.J_m4 = d.I_x_m4 + d.I_y_m4;
      }
      break;
    }
    case Shape::kCustom:
      d.area_m2 = area_profile.slope(s, side);
      d.I_x_m4 = I_x_profile.slope(s, side);
      d.I_y_m4 = I_y_profile.slope(s, side);
      d.J_m4 = J_profile.slope(s, side);
      break;
  }
  return d;
}

bool Section::varies() const {
  return !(width_profile.is_constant() && height_profile.is_constant() &&
           area_profile.is_constant() && I_x_profile.is_constant() && I_y_profile.is_constant() &&
           J_profile.is_constant());
}

bool BodyMaterial::varies() const {
  return !(youngs_modulus_profile.is_constant() && density_profile.is_constant());
}

MaterialProperties BodyMaterial::properties_at(double s, Side side) const {
  MaterialProperties p;
  p.youngs_modulus_Pa = youngs_modulus_profile.value(s, side);
  p.shear_modulus_Pa = shear_modulus(p.youngs_modulus_Pa);
  p.density_kg_m3 = density_profile.value(s, side);
  p.viscosity_Pa_s = viscosity_profile.value(s, side);
  return p;
}

SectionStiffness section_stiffness(const SectionProperties& p, double E, double G) {
  // [Pawlowski2019] text below Eq. (12): K_nu = diag(G A, G A, E A) (no shear correction
  // factor), K_omega = diag(E I_x, E I_y, G J).
  SectionStiffness k;
  k.shear_extension = {G * p.area_m2, G * p.area_m2, E * p.area_m2};
  k.bending_torsion = {E * p.I_x_m4, E * p.I_y_m4, G * p.J_m4};
  return k;
}

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
      return 0.5 * width_profile.value(0.0);
    case Shape::kRectangle: {
      // The ray t (c, s) leaves the rectangle |x| <= w/2, |y| <= h/2 at the first edge it
      // meets; a zero component never limits it.
      const double tx = c > 0.0 ? 0.5 * width_profile.value(0.0) / c : HUGE_VAL;
      const double ty = s > 0.0 ? 0.5 * height_profile.value(0.0) / s : HUGE_VAL;
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

Eigen::Vector3d Routing::r(double s_m, Side side) const {
  if (type == Type::kStraight) return {offset_m.x(), offset_m.y(), 0.0};
  if (type == Type::kSpline) return spline_eval(s_m, side, 0);
  // r(s) = R (cos theta, sin theta, 0)
  const double theta = helix_angle(*this, s_m);
  return {radius_m * std::cos(theta), radius_m * std::sin(theta), 0.0};
}

Eigen::Vector3d Routing::dr(double s_m, Side side) const {
  if (type == Type::kStraight) return Eigen::Vector3d::Zero();
  if (type == Type::kSpline) return spline_eval(s_m, side, 1);
  // r'(s) = R w (-sin theta, cos theta, 0), w = 2 pi k
  const double w = 2.0 * units::kPi * turns_per_m;
  const double theta = helix_angle(*this, s_m);
  return {-radius_m * w * std::sin(theta), radius_m * w * std::cos(theta), 0.0};
}

Eigen::Vector3d Routing::ddr(double s_m, Side side) const {
  if (type == Type::kStraight) return Eigen::Vector3d::Zero();
  if (type == Type::kSpline) return spline_eval(s_m, side, 2);
  // r''(s) = -R w^2 (cos theta, sin theta, 0)
  const double w = 2.0 * units::kPi * turns_per_m;
  const double theta = helix_angle(*this, s_m);
  return {-radius_m * w * w * std::cos(theta), -radius_m * w * w * std::sin(theta), 0.0};
}

bool RodModel::uniform_body() const {
  return !section.varies() && !material.varies() && reference_curvature_profile[0].is_constant() &&
         reference_curvature_profile[1].is_constant() &&
         reference_curvature_profile[2].is_constant();
}

SectionStiffness RodModel::stiffness_at(double s, Side side) const {
  const double E = material.youngs_modulus_profile.value(s, side);
  return section_stiffness(section.properties_at(s, side), E, material.shear_modulus(E));
}

Eigen::Vector3d RodModel::shear_extension_stiffness(double s, Side side) const {
  return stiffness_at(s, side).shear_extension;
}

Eigen::Vector3d RodModel::bending_torsion_stiffness(double s, Side side) const {
  return stiffness_at(s, side).bending_torsion;
}

double RodModel::mass_per_length_kg_m(double s, Side side) const {
  return material.density_profile.value(s, side) * section.properties_at(s, side).area_m2;
}

Eigen::Vector3d RodModel::weight_per_length_W_N_m() const {
  // [Pawlowski2019] Eq. (14), corrected (docs/conventions.md): psi A g in the world frame.
  return mass_per_length_kg_m(0.0) * gravity_W_m_s2;
}

Eigen::Vector3d RodModel::reference_curvature_at(double s, Side side) const {
  return {reference_curvature_profile[0].value(s, side),
          reference_curvature_profile[1].value(s, side),
          reference_curvature_profile[2].value(s, side)};
}

void RodModel::set_reference_curvature(const Eigen::Vector3d& omega_B_1_m) {
  for (int c = 0; c < 3; ++c) reference_curvature_profile[c] = Profile(omega_B_1_m[c]);
}

void RodModel::property_slopes(double s, Side side, Eigen::Vector3d& dK_se, Eigen::Vector3d& dK_bt,
                               Eigen::Vector3d& domega_star) const {
  if (uniform_body()) {
    dK_se.setZero();
    dK_bt.setZero();
    domega_star.setZero();
    return;
  }
  const SectionProperties p = section.properties_at(s, side);
  const SectionProperties dp = section.derivatives_at(s, side);
  // d/ds of section_stiffness(p, E, G) with G = c E (BodyMaterial::shear_modulus is linear in E):
  // the product rule on each diagonal entry.
  const double c = 1.0 / (2.0 * (1.0 + material.poisson_ratio));
  const double E = material.youngs_modulus_profile.value(s, side);
  const double dE = material.youngs_modulus_profile.slope(s, side);
  const double dGA = c * (dE * p.area_m2 + E * dp.area_m2);
  dK_se = {dGA, dGA, dE * p.area_m2 + E * dp.area_m2};
  dK_bt = {dE * p.I_x_m4 + E * dp.I_x_m4, dE * p.I_y_m4 + E * dp.I_y_m4,
           c * (dE * p.J_m4 + E * dp.J_m4)};
  domega_star = {reference_curvature_profile[0].slope(s, side),
                 reference_curvature_profile[1].slope(s, side),
                 reference_curvature_profile[2].slope(s, side)};
}

std::vector<double> RodModel::breakpoints() const {
  std::vector<double> all;
  const Profile* profiles[] = {&section.width_profile,
                               &section.height_profile,
                               &section.area_profile,
                               &section.I_x_profile,
                               &section.I_y_profile,
                               &section.J_profile,
                               &material.youngs_modulus_profile,
                               &material.density_profile,
                               &reference_curvature_profile[0],
                               &reference_curvature_profile[1],
                               &reference_curvature_profile[2]};
  for (const Profile* p : profiles) {
    for (double s : p->breakpoints()) {
      if (s > 0.0 && s < length_m) all.push_back(s);
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

bool RodModel::jumps_at(double s) const {
  return shear_extension_stiffness(s, Side::kLeft) != shear_extension_stiffness(s, Side::kRight) ||
         bending_torsion_stiffness(s, Side::kLeft) != bending_torsion_stiffness(s, Side::kRight) ||
         mass_per_length_kg_m(s, Side::kLeft) != mass_per_length_kg_m(s, Side::kRight) ||
         reference_curvature_at(s, Side::kLeft) != reference_curvature_at(s, Side::kRight);
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
