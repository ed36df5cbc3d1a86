#pragma once
/// Rod models built in code for the beam FE tests and benchmark (independent of the
/// scenario parser).
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "common/units.hpp"
#include "rod/model.hpp"
#include "rod/scenario.hpp"
#include "tca/tca.hpp"

namespace tcasim::beam_fe::testing {

/// A rod along body e3 with given stiffnesses EA, GA, EI_x, EI_y, GJ (E = 1 Pa, custom section).
inline rod::RodModel stiffness_rod(double length_m, double EA, double GA, double EI_x, double EI_y,
                                   double GJ) {
  rod::RodModel m;
  m.name = "stiffness-rod";
  m.length_m = length_m;
  m.section.shape = rod::Section::Shape::kCustom;
  m.material.youngs_modulus_Pa = 1.0;
  m.material.shear_modulus_Pa = GA / EA;
  m.section.area_m2 = EA;
  m.section.I_x_m4 = EI_x;
  m.section.I_y_m4 = EI_y;
  m.section.J_m4 = GJ / m.material.shear_modulus_Pa;
  return m;
}

/// A uniform rod with a circular section of diameter d (polar J).
inline rod::RodModel circular_rod(double length_m, double diameter_m, double E_Pa, double poisson,
                                  double density_kg_m3) {
  rod::RodModel m;
  m.name = "circular-rod";
  m.length_m = length_m;
  m.section.shape = rod::Section::Shape::kCircle;
  m.section.width_m = diameter_m;
  m.section.height_m = diameter_m;
  m.section.area_m2 = units::kPi * diameter_m * diameter_m / 4.0;
  m.section.I_x_m4 = units::kPi * std::pow(diameter_m, 4) / 64.0;
  m.section.I_y_m4 = m.section.I_x_m4;
  m.section.J_m4 = 2.0 * m.section.I_x_m4;
  m.material.youngs_modulus_Pa = E_Pa;
  m.material.poisson_ratio = poisson;
  m.material.shear_modulus_Pa = E_Pa / (2.0 * (1.0 + poisson));
  m.material.density_kg_m3 = density_kg_m3;
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
  a.length_ratio = a.rest_length_m / m.length_m;
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
  return std::make_shared<const tca::Tca>(p, rod::load_material("silver-nylon-sun2022", "material"));
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
  a.length_ratio = a.rest_length_m / m.length_m;
  m.tcas["tca"] = std::move(tca);
  m.actuators.push_back(a);
}

/// The paper's circular manipulator (Section V-B): 8 mm diameter, 40 mm, EcoFlex
/// (E = 37.8 kPa, nu = 0.5, 1040 kg/m^3), one extension TCA at +3 mm along body x,
/// standing on its base (gravity -z), initial bending omega* = (0, -0.5, 0) 1/m (the
/// paper gives none; the same value as the shooting-solver tests).
inline rod::RodModel circular_manipulator(double temperature_K) {
  rod::RodModel m = circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  m.name = "circular-manipulator";
  m.reference_curvature_B_1_m = {0.0, -0.5, 0.0};
  m.gravity_W_m_s2 = {0.0, 0.0, -9.81};
  add_tca_string(m, "tca", manipulator_tca(), 0.003, 0.0, temperature_K);
  return m;
}

}  // namespace tcasim::beam_fe::testing
