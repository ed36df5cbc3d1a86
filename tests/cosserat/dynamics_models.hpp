#pragma once
/// Models of the rod-dynamics tests and benchmark: the steel cantilever of [Till2019]'s
/// dynamics example (E 200 GPa, G 80 GPa, r 1 mm, rho 8000 kg/m^3, L 0.5 m), base along
/// +z, gravity along -x (a horizontal cantilever turned on its side).
#include <Eigen/Core>

#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "support/rod_models.hpp"

namespace tcasim::cosserat::testing {

/// The steel cantilever with G = 80 GPa exactly (poisson 0.25) and radius r_m.
inline rod::RodModel steel_cantilever(double r_m = 1e-3, double length_m = 0.5) {
  rod::RodModel m = test_support::circular_rod(length_m, 2.0 * r_m, 200e9, 0.25, 8000.0);
  m.name = "steel-cantilever";
  return m;
}

/// Gravity along -x and a tip weight of `tip_mass_kg` (its weight as a tip force).
inline rod::Loads sag_loads(const rod::RodModel& m, double tip_mass_kg) {
  rod::Loads l = rod::Loads::from_model(m);
  l.gravity_W_m_s2 = Eigen::Vector3d(-9.81, 0.0, 0.0);
  l.tip_force_W_N = tip_mass_kg * l.gravity_W_m_s2;
  return l;
}

}  // namespace tcasim::cosserat::testing
