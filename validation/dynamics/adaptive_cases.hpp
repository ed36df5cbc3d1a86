#pragma once
/// validate_dynamics step 9 (validation/dynamics/adaptive_cases.cpp): error-controlled time steps
/// (method::run_adaptive, `tcasim simulate --rtol`) in both dynamics methods (issue 35).
#include <string>

#include "validation/common/gates.hpp"

namespace tcasim::dynamics_validation {

/// Step 9: the released steel cantilever, the manipulator's voltage step and its PWM drive with
/// adaptive steps; writes adaptive.csv, adaptive_order.csv and adaptive_agreement.csv.
void adaptive_steps(validation::Gates& g, const std::string& out_dir, bool quick);

}  // namespace tcasim::dynamics_validation
