#pragma once
// Materials and TCAs for the tca tests, built in code so the tests do not depend on the
// scenario parser. Values follow data/materials/*.json and docs/conventions.md "TCA material data".
#include "common/units.hpp"
#include "tca/tca.hpp"

namespace tcasim::tca::testing {

/// silver-nylon-sun2022: constant E, G; diameter ratio polynomial (Sun & Zhao 2022).
inline Material sun2022() {
  Material m;
  m.name = "silver-nylon-sun2022";
  m.source = "test copy of data/materials/silver-nylon-sun2022.json";
  m.reference_temperature_K = units::degC_to_K(25.0);
  m.youngs_modulus_Pa.coefficients = {1.198e9};
  m.shear_modulus_Pa.coefficients = {0.2218e9};
  m.diameter.type = DiameterLaw::Type::kRatioPolynomial;
  m.diameter.ratio_polynomial.coefficients = {1.00169, -6.705e-5, 3.542e-6};
  m.f12_form = F12Form::kCastigliano;
  m.min_temperature_K = units::degC_to_K(25.0);
  m.max_temperature_K = units::degC_to_K(160.0);
  return m;
}

/// A material with every property temperature dependent (exercises all derivative terms):
/// E and G soften linearly and quadratically, linear diameter expansion.
inline Material softening() {
  Material m;
  m.name = "softening-test";
  m.reference_temperature_K = units::degC_to_K(25.0);
  m.youngs_modulus_Pa.coefficients = {2.3e9, -5.0e6};
  m.shear_modulus_Pa.coefficients = {0.45e9, -1.0e6, -2.0e3};
  m.diameter.type = DiameterLaw::Type::kLinearExpansion;
  m.diameter.linear_expansion_1_K = 6e-4;
  m.min_temperature_K = units::degC_to_K(0.0);
  m.max_temperature_K = units::degC_to_K(180.0);
  return m;
}

/// The 3-thread TCA of Fig. 5 (l and L as corrected in docs/conventions.md "TCA data of the paper's
/// experiments").
inline Parameters three_thread(Kind kind = Kind::kExtension, F12Form form = F12Form::kCastigliano) {
  Parameters p;
  p.kind = kind;
  p.coiled_length_m = 0.110;
  p.fiber_length_m = 0.497;
  p.outer_diameter_m = 0.002;
  p.twist_turns = 300;
  p.f12_form = form;
  return p;
}

/// The 4-thread TCA of Fig. 5.
inline Parameters four_thread(Kind kind = Kind::kExtension, F12Form form = F12Form::kCastigliano) {
  Parameters p;
  p.kind = kind;
  p.coiled_length_m = 0.110;
  p.fiber_length_m = 0.471;
  p.outer_diameter_m = 0.00213;
  p.twist_turns = 259;
  p.f12_form = form;
  return p;
}

/// Nylon 6,6 of the open-coil monocoil below: E = 1.925 GPa, G = E/3, rho = 8e-5 1/K
/// (data/tca/liuyang-monocoil/README.md).
inline Material nylon_monocoil() {
  Material m;
  m.name = "nylon-monocoil-test";
  m.reference_temperature_K = units::degC_to_K(25.0);
  m.youngs_modulus_Pa.coefficients = {1.925e9};
  m.shear_modulus_Pa.coefficients = {1.925e9 / 3.0};
  m.diameter.type = DiameterLaw::Type::kLinearExpansion;
  m.diameter.linear_expansion_1_K = 8e-5;
  m.min_temperature_K = units::degC_to_K(0.0);
  m.max_temperature_K = units::degC_to_K(180.0);
  return m;
}
/// An open-coil contraction monocoil with a measured fiber: d0 = 0.74 mm, helix mean
/// diameter 1.632 mm, L = 25 mm, 18.3 coils (732 per metre), N = 47.3 twist turns.
inline Parameters open_monocoil(Kind kind = Kind::kContraction) {
  Parameters p;
  p.kind = kind;
  p.coiled_length_m = 0.025;
  p.fiber_diameter_m = 0.74e-3;
  p.outer_diameter_m = 1.632e-3 + 0.74e-3;
  p.fiber_length_m = fiber_length_from_coil_count(0.025, 1.632e-3, 732.0 * 0.025);
  p.twist_turns = 47.3;
  p.f12_form = F12Form::kCastigliano;
  return p;
}

inline double K(double t_degC) { return units::degC_to_K(t_degC); }

}  // namespace tcasim::tca::testing
