#pragma once
/// Rod models built in code for the solver tests and benchmarks (no scenario files: these
/// tests must not depend on the parser). Shared by tests/cosserat, tests/beam_fe and bench/.
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "common/units.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/scenario.hpp"
#include "tca/tca.hpp"

namespace tcasim::test_support {

/// A uniform rod along +z from the origin with a circular section of diameter d.
inline rod::RodModel circular_rod(double length_m, double diameter_m, double E_Pa, double poisson,
                                  double density_kg_m3) {
  rod::RodModel m;
  m.name = "circular-rod";
  m.length_m = length_m;
  m.section.shape = rod::Section::Shape::kCircle;
  m.section.width_profile = rod::Profile(diameter_m);
  m.section.height_profile = rod::Profile(diameter_m);
  m.material.youngs_modulus_profile = rod::Profile(E_Pa);
  m.material.poisson_ratio = poisson;
  m.material.density_profile = rod::Profile(density_kg_m3);
  return m;
}

/// A square section of side a (polar moment as torsion constant, as the paper does).
inline rod::RodModel square_rod(double length_m, double side_m, double E_Pa, double poisson,
                                double density_kg_m3) {
  rod::RodModel m = circular_rod(length_m, side_m, E_Pa, poisson, density_kg_m3);
  m.name = "square-rod";
  m.section.shape = rod::Section::Shape::kRectangle;  // width = height = side
  return m;
}

/// A rod along body e3 with given stiffnesses EA, GA, EI_x, EI_y, GJ (E = 1 Pa, custom section;
/// the Poisson ratio that makes G / E = GA / EA, so GA and GJ hold to round-off).
inline rod::RodModel stiffness_rod(double length_m, double EA, double GA, double EI_x, double EI_y,
                                   double GJ) {
  rod::RodModel m;
  m.name = "stiffness-rod";
  m.length_m = length_m;
  m.section.shape = rod::Section::Shape::kCustom;
  m.material.youngs_modulus_profile = rod::Profile(1.0);
  m.material.poisson_ratio = EA / (2.0 * GA) - 1.0;  // G = E / (2 (1 + nu)) = GA / EA
  m.section.area_profile = rod::Profile(EA);
  m.section.I_x_profile = rod::Profile(EI_x);
  m.section.I_y_profile = rod::Profile(EI_y);
  m.section.J_profile = rod::Profile(GJ / m.material.shear_modulus(1.0));
  return m;
}

/// A custom section with given stiffnesses: EA, GA, EI (both axes), GJ (E = 1 Pa).
inline rod::RodModel custom_rod(double length_m, double EA, double GA, double EI, double GJ) {
  rod::RodModel m = stiffness_rod(length_m, EA, GA, EI, EI, GJ);
  m.name = "custom-rod";
  return m;
}

/// Appends a tension-driven string (straight at (x, y), or a helix when turns_per_m != 0).
inline void add_tension_string(rod::RodModel& m, const std::string& name, double x_m, double y_m,
                               double tension_N, int count = 1, double turns_per_m = 0.0) {
  rod::Actuator a;
  a.name = name;
  a.count = count;
  if (turns_per_m == 0.0) {
    a.routing.type = rod::Routing::Type::kStraight;
    a.routing.offset_m = {x_m, y_m};
    a.rest_length_m = m.length_m;
  } else {
    a.routing.type = rod::Routing::Type::kHelix;
    a.routing.radius_m = std::hypot(x_m, y_m);
    a.routing.phase_rad = std::atan2(y_m, x_m);
    a.routing.turns_per_m = turns_per_m;
    const double w = 2.0 * units::kPi * turns_per_m * a.routing.radius_m;
    a.rest_length_m = std::sqrt(1.0 + w * w) * m.length_m;
  }
  a.drive.type = rod::Drive::Type::kTension;
  a.drive.tension_N = tension_N;
  m.actuators.push_back(a);
}

/// The paper's manipulator TCA ([Pawlowski2019] Section V-B): extension, D = 1.7 mm,
/// alpha0 = 15 deg, N = 76.4 turns, coiled length 40 mm, silver-nylon-sun2022.
inline std::shared_ptr<const tca::Tca> manipulator_tca() {
  tca::Parameters p;
  p.kind = tca::Kind::kExtension;
  p.coiled_length_m = 0.040;
  p.fiber_length_m = tca::fiber_length_from_pitch(0.040, units::deg_to_rad(15.0));
  p.outer_diameter_m = 0.0017;
  p.twist_turns = 76.4;
  p.f12_form = tca::F12Form::kCastigliano;
  return std::make_shared<const tca::Tca>(p,
                                          rod::load_material("silver-nylon-sun2022", "material"));
}

/// Appends a TCA-driven straight string at (x, y) at uniform temperature t_K.
inline void add_tca_string(rod::RodModel& m, const std::string& name,
                           std::shared_ptr<const tca::Tca> tca, double x_m, double y_m, double t_K,
                           int count = 1) {
  rod::Actuator a;
  a.name = name;
  a.routing.type = rod::Routing::Type::kStraight;
  a.routing.offset_m = {x_m, y_m};
  a.count = count;
  a.drive.type = rod::Drive::Type::kTca;
  a.drive.tca_id = "tca";
  a.drive.tca = tca;
  a.drive.segments = {tca::Segment{1.0, t_K}};
  a.rest_length_m = tca->parameters().coiled_length_m;
  m.tcas["tca"] = std::move(tca);
  m.actuators.push_back(a);
}

/// A frictionless plane obstacle named `name` through `point` with unit normal `normal` (the
/// free side), by default the floor z = 0.
inline rod::Obstacle plane_obstacle(const std::string& name = "floor",
                                    const Eigen::Vector3d& point = Eigen::Vector3d::Zero(),
                                    const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
  rod::Obstacle o;
  o.name = name;
  o.type = rod::Obstacle::Type::kPlane;
  o.point_W_m = point;
  o.direction_W = normal.normalized();
  return o;
}

/// Initial bending of the circular manipulator (docs/conventions.md "Initial bending": it
/// has one; the paper gives no value): omega* = (0, -0.5, 0) 1/m bends it toward -x, away from the
/// TCA, so the cold TCA is slightly stretched (delta > 0, coils open).
inline const Eigen::Vector3d kCircularInitialCurvature_1_m{0.0, -0.5, 0.0};
/// Gravity: the manipulators stand on their base with the centerline along +z, so
/// gravity is along -z.
inline const Eigen::Vector3d kStandingGravity_m_s2{0.0, 0.0, -9.81};

/// The paper's circular manipulator (Section V-B): 8 mm diameter, 40 mm long, EcoFlex
/// (E = 37.8 kPa, nu = 0.5, 1040 kg/m^3), one extension TCA at +3 mm along body x.
inline rod::RodModel circular_manipulator(double temperature_K) {
  rod::RodModel m = circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  m.name = "circular-manipulator";
  m.set_reference_curvature(kCircularInitialCurvature_1_m);
  m.gravity_W_m_s2 = kStandingGravity_m_s2;
  add_tca_string(m, "tca", manipulator_tca(), 0.003, 0.0, temperature_K);
  return m;
}

/// The paper's square manipulator (Section V-B): 10 mm square, 40 mm, U-shaped TCA
/// (count 2) at +3 mm along body x, no initial bending.
inline rod::RodModel square_manipulator(double temperature_K) {
  rod::RodModel m = square_rod(0.040, 0.010, 37.8e3, 0.5, 1040.0);
  m.name = "square-manipulator";
  m.gravity_W_m_s2 = kStandingGravity_m_s2;
  add_tca_string(m, "tca", manipulator_tca(), 0.003, 0.0, temperature_K, 2);
  return m;
}

/// The steel cantilever of [Till2019] (E 200 GPa, poisson 0.25, r 1 mm, rho 8000, L 0.5 m).
inline rod::RodModel steel_cantilever_till() {
  return circular_rod(0.5, 2e-3, 200e9, 0.25, 8000.0);
}

/// steel_cantilever_till with two tensioned strings, a straight one and a helix.
inline rod::RodModel steel_cantilever_with_strings() {
  rod::RodModel m = steel_cantilever_till();
  add_tension_string(m, "straight", 0.8e-3, 0.0, 2.0);
  add_tension_string(m, "helix", 0.0, 0.7e-3, 1.0, 1, 2.0);
  return m;
}

/// The model's loads with gravity along -x and the weight of `tip_kg` as a tip force.
inline rod::Loads sag(const rod::RodModel& m, double tip_kg) {
  rod::Loads l = rod::Loads::from_model(m);
  l.gravity_W_m_s2 = Eigen::Vector3d(-9.81, 0.0, 0.0);
  l.tip_force_W_N = tip_kg * l.gravity_W_m_s2;
  return l;
}

/// 4-tendon steel rod: E = 200 GPa, G = 80 GPa, r = 1 mm, L = 0.5 m, 8000 kg/m^3,
/// gravity 9.81 along +x, tendons at 15.06 mm at 0/90/180/270 deg, tensions (15, 0, 0, 0) N.
inline rod::RodModel steel_tendon_rod() {
  rod::RodModel m = circular_rod(0.5, 0.002, 200e9, 0.25, 8000.0);  // G = 200e9 / 2.5 = 80e9
  m.name = "steel-4-tendon";
  m.gravity_W_m_s2 = {9.81, 0.0, 0.0};
  const double r = 0.01506;
  add_tension_string(m, "t0", r, 0.0, 15.0);
  add_tension_string(m, "t90", 0.0, r, 0.0);
  add_tension_string(m, "t180", -r, 0.0, 0.0);
  add_tension_string(m, "t270", 0.0, -r, 0.0);
  return m;
}

/// The closed-coil closed form (docs/conventions.md "Closed coils"): a massless square rod
/// (the square manipulator's body) with the manipulator TCA at (+3 mm, 0) at temperature t_K
/// and a tendon on the centerline pulling the tip toward the base with tension P. While
/// P is large enough that the TCA's coils stay closed (its tension below the blocked force),
/// the TCA is a rigid strut, delta = 0, and the strains are the closed form of straight
/// strings with the strut tension T_s that keeps delta = 0.
inline rod::RodModel strut_rod(double load_N, double t_K) {
  rod::RodModel m = square_rod(0.040, 0.010, 37.8e3, 0.5, 0.0);
  m.name = "strut-rod";
  add_tca_string(m, "tca", manipulator_tca(), 0.003, 0.0, t_K);
  add_tension_string(m, "load", 0.0, 0.0, load_N);
  return m;
}

/// An open-coil contraction TCA with a measured fiber (docs/conventions.md "Measured fiber
/// diameter"): L = 40 mm, D = 1.7 mm, d0 = 0.3 mm, 20 coils (pitch 2 mm), closed length
/// n d0 = 6 mm, N = 20 turns, silver-nylon-sun2022.
inline std::shared_ptr<const tca::Tca> open_coil_tca() {
  tca::Parameters p;
  p.kind = tca::Kind::kContraction;
  p.coiled_length_m = 0.040;
  p.outer_diameter_m = 0.0017;
  p.fiber_diameter_m = 0.0003;
  p.fiber_length_m = tca::fiber_length_from_coil_count(0.040, 0.0017 - 0.0003, 20.0);
  p.twist_turns = 20.0;
  p.f12_form = tca::F12Form::kCastigliano;
  return std::make_shared<const tca::Tca>(p,
                                          rod::load_material("silver-nylon-sun2022", "material"));
}

/// strut_rod with the open-coil TCA of open_coil_tca pre-elongated to its closed length
/// (rest length L - delta_c): in the reference shape its coils touch, and the tendon load P
/// holds them so; the strut closed form below holds with delta = delta_c.
inline rod::RodModel open_coil_strut_rod(double load_N, double t_K) {
  rod::RodModel m = square_rod(0.040, 0.010, 37.8e3, 0.5, 0.0);
  m.name = "open-coil-strut-rod";
  const auto tca = open_coil_tca();
  const double dc = tca->closed_elongation_m();
  add_tca_string(m, "tca", tca, 0.003, 0.0, t_K);
  m.actuators[0].rest_length_m = m.length_m - dc;
  add_tension_string(m, "load", 0.0, 0.0, load_N);
  return m;
}

/// The rigid-strut state of strut_rod: strut tension T_s, axial strain nu3, curvature
/// kappa = omega_y and the tip position (p_x, 0, p_z).
struct StrutClosedForm {
  double strut_tension_N, nu3, kappa_1_m;
  Eigen::Vector3d tip_W_m;
};

/// Closed form (straight strings, docs/conventions.md "Closed form"): nu3 = 1 - (T_s + P)/(E A),
/// omega_y = T_s x / (E I_y), delta = L (nu3 - omega_y x) - L = 0 gives
/// T_s = -P (1/(E A)) / (1/(E A) + x^2/(E I_y)); the arc p = nu3 ((1 - cos kL)/k, 0, sin(kL)/k).
inline StrutClosedForm strut_closed_form(const rod::RodModel& m) {
  const double EA = m.shear_extension_stiffness().z(), EIy = m.bending_torsion_stiffness().y();
  const double x = m.actuators[0].routing.offset_m.x(), P = m.actuators[1].drive.tension_N;
  const double L = m.length_m;
  StrutClosedForm c{};
  c.strut_tension_N = -P * (1.0 / EA) / (1.0 / EA + x * x / EIy);
  c.nu3 = 1.0 - (c.strut_tension_N + P) / EA;
  c.kappa_1_m = c.strut_tension_N * x / EIy;
  const double k = c.kappa_1_m;
  c.tip_W_m = c.nu3 * Eigen::Vector3d((1.0 - std::cos(k * L)) / k, 0.0, std::sin(k * L) / k);
  return c;
}

}  // namespace tcasim::test_support
