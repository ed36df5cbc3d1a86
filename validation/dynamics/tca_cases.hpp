#pragma once
/// validate_dynamics steps 7 and 8 (validation/dynamics/tca_cases.cpp): the PWM-driven three-TCA
/// rod in 3-D and the heated quasi-static limit.
#include <fstream>
#include <string>
#include <vector>

#include "validation/common/gates.hpp"

namespace tcasim::dynamics_validation {

/// Writes the observed orders of a ladder (h decreasing) to `csv` (study,h,error,observed_order)
/// and gates the smallest and the largest in [expected - tol, expected + tol]
/// (validation/dynamics/dynamics.cpp).
void gate_orders(validation::Gates& g, const std::string& name, const std::vector<double>& h,
                 const std::vector<double>& e, double expected, double tol, std::ofstream& csv);

/// Step 7: validation/scenarios/three-tca-pwm.json; writes pwm.csv and pwm_quasi_static.csv.
void pwm_three_tca(validation::Gates& g, const std::string& out_dir, bool quick);
/// Step 8: the circular manipulator heated by slow temperature ramps; writes heated_ramp.csv.
void heated_quasi_static(validation::Gates& g, const std::string& out_dir, bool quick);

}  // namespace tcasim::dynamics_validation
