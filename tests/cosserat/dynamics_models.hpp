#pragma once
/// Models of the rod-dynamics tests and benchmark: the steel cantilever of [Till2019]'s
/// dynamics example (E 200 GPa, G 80 GPa, r 1 mm, rho 8000 kg/m^3, L 0.5 m), base along
/// +z, gravity along -x (a horizontal cantilever turned on its side).
#include <Eigen/Core>

#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/scenario.hpp"
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

/// A varying steel cantilever (L 0.5 m): the diameter tapers from 2.4 to 1.8 mm over
/// [0, 0.3], jumps to 1.5 mm and tapers to 1.2 mm at the tip; the reference curvature about
/// body y grows linearly to 0.5 1/m; the viscosity (used only where a test says) grows from
/// 1e7 to 3e7 Pa s. Breakpoints at 0.3 (a jump) and nowhere else.
inline rod::RodModel tapered_steel_cantilever() {
  return rod::parse_scenario(nlohmann::json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "tapered-steel-cantilever",
    "body": {"length_m": 0.5,
             "section": {"shape": "circle",
                         "diameter_m": {"s_m": [0, 0.3, 0.3, 0.5],
                                        "values": [2.4e-3, 1.8e-3, 1.5e-3, 1.2e-3]}},
             "material": {"youngs_modulus_Pa": 200e9, "poisson_ratio": 0.25,
                          "density_kg_m3": 8000,
                          "viscosity_Pa_s": {"s_m": [0, 0.5], "values": [1e7, 3e7]}},
             "reference_curvature_1_m": [0, {"s_m": [0, 0.5], "values": [0, 0.5]}, 0]},
    "actuators": []})"));
}

}  // namespace tcasim::cosserat::testing
