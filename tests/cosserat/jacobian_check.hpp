#pragma once
/// The shooting Jacobian by forward sensitivities against central differences at one point.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>

#include "cosserat/shooting.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::cosserat::testing {

/// Worst column-relative difference of the sensitivity and central-difference Jacobians of
/// `m` (six strain unknowns and one TCA tension) at a fixed, generic point, with `o`'s
/// integrator; a test failure if either Jacobian is not available.
inline double sensitivity_vs_central_difference(const rod::RodModel& m, Options o) {
  Eigen::VectorXd x(7);
  x << 0.01, -0.02, -0.01, 2.0, -5.0, 1.0, -0.002;
  ShootingSolver sens(m, o);
  o.jacobian = JacobianMethod::kCentralDifference;
  ShootingSolver cen(m, o);
  Eigen::MatrixXd Js, Jc;
  EXPECT_TRUE(sens.jacobian(rod::Loads::from_model(m), x, Js));
  EXPECT_TRUE(cen.jacobian(rod::Loads::from_model(m), x, Jc));
  if (Js.size() == 0 || Js.rows() != Jc.rows() || Js.cols() != Jc.cols()) return HUGE_VAL;
  return test_support::worst_column_relative_difference(Js, Jc);
}

}  // namespace tcasim::cosserat::testing
