// Tests of the test helpers themselves: finite differences and observed orders.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "support/convergence.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::test_support {
namespace {

// Central differences with the cbrt(eps) rule: error ~ eps^(2/3) ~ 4e-11 times the
// size of the third derivative; 1e-9 allows derivatives of size ~10.
constexpr double kFdTol = 1e-9;

TEST(SupportFiniteDifference, StepRuleScalesWithMagnitudeAndIsRepresentable) {
  const double rel = default_relative_step();
  EXPECT_NEAR(rel, std::cbrt(2.220446049250313e-16), 1e-20);
  EXPECT_NEAR(central_difference_step(0.0, rel), rel, 1e-20);
  EXPECT_NEAR(central_difference_step(1e4, rel), 1e4 * rel, 1e4 * rel * 1e-10);
  const double x = 123.456;
  const double h = central_difference_step(x, rel);
  EXPECT_EQ((x + h) - x, h) << "step must be exactly representable at x";
}

TEST(SupportFiniteDifference, ScalarDerivativeMatchesAnalytic) {
  // O(1) arguments: the rule assumes f varies on the scale max(1, |x|), which sin
  // does not at large |x| (there h ~ 3e-4 would give a 1e-8 truncation error).
  for (double x : {-2.0, 0.0, 0.7, 3.0}) {
    EXPECT_NEAR(derivative([](double t) { return std::sin(t); }, x), std::cos(x), kFdTol) << x;
  }
  // Relative accuracy for a large argument (the step scales with |x|).
  const double x = 1e3;
  EXPECT_NEAR(derivative([](double t) { return t * t * t; }, x) / (3.0 * x * x), 1.0, kFdTol);
}

TEST(SupportFiniteDifference, GradientAndJacobianMatchAnalytic) {
  const auto f = [](const Eigen::VectorXd& v) { return std::exp(v[0]) * std::sin(v[1]) + v[2] * v[2]; };
  Eigen::VectorXd x(3);
  x << 0.3, -1.1, 2.0;
  Eigen::VectorXd g_exact(3);
  g_exact << std::exp(x[0]) * std::sin(x[1]), std::exp(x[0]) * std::cos(x[1]), 2.0 * x[2];
  EXPECT_LE((gradient(f, x) - g_exact).norm(), kFdTol);

  const auto F = [](const Eigen::VectorXd& v) {
    Eigen::VectorXd out(2);
    out << v[0] * v[1], std::cos(v[2]) + v[0];
    return out;
  };
  Eigen::MatrixXd J_exact(2, 3);
  J_exact << x[1], x[0], 0.0, 1.0, 0.0, -std::sin(x[2]);
  const Eigen::MatrixXd J = jacobian(F, x);
  ASSERT_EQ(J.rows(), 2);
  ASSERT_EQ(J.cols(), 3);
  EXPECT_LE((J - J_exact).norm(), kFdTol);
}

TEST(SupportConvergence, ObservedOrdersRecoverPowerLawForUnevenRatios) {
  const std::vector<double> h = {0.1, 0.05, 0.02, 0.015, 0.001};
  std::vector<double> e;
  for (double hi : h) e.push_back(3.0 * std::pow(hi, 2.5));
  const std::vector<double> p = observed_orders(h, e);
  ASSERT_EQ(p.size(), h.size() - 1);
  for (double pi : p) EXPECT_NEAR(pi, 2.5, 1e-12);
}

TEST(SupportConvergence, ObservedOrdersRejectBadInputAndGiveNanForZeroError) {
  EXPECT_THROW(observed_orders({0.1, 0.05}, {1.0}), std::invalid_argument);
  EXPECT_THROW(observed_orders({0.1}, {1.0}), std::invalid_argument);
  EXPECT_THROW(observed_orders({0.1, 0.1}, {1.0, 0.5}), std::invalid_argument);
  EXPECT_THROW(observed_orders({0.1, -0.05}, {1.0, 0.5}), std::invalid_argument);
  EXPECT_TRUE(std::isnan(observed_orders({0.1, 0.05}, {1.0, 0.0})[0]));
}

TEST(SupportConvergence, BracketAcceptsInsideAndRejectsBelowAndAbove) {
  const std::vector<double> h = {0.4, 0.2, 0.1, 0.05};
  std::vector<double> e2, e4;
  for (double hi : h) {
    e2.push_back(std::pow(hi, 2.0));
    e4.push_back(std::pow(hi, 4.0));
  }
  EXPECT_TRUE(OrderInBracket(h, e2, 2.0, 0.1));
  EXPECT_FALSE(OrderInBracket(h, e2, 4.0, 0.15)) << "order below the bracket must fail";
  EXPECT_FALSE(OrderInBracket(h, e4, 2.0, 0.15)) << "order above the bracket must fail";
  // A pre-asymptotic first level can be skipped with first_checked.
  std::vector<double> e_pre = e2;
  e_pre[0] *= 10.0;
  EXPECT_FALSE(OrderInBracket(h, e_pre, 2.0, 0.1));
  EXPECT_TRUE(OrderInBracket(h, e_pre, 2.0, 0.1, 1));
}

TEST(SupportConvergence, FailureMessagePrintsTheWholeTable) {
  const std::vector<double> h = {0.4, 0.2, 0.1};
  const std::vector<double> e = {0.16, 0.04, 0.01};
  const ::testing::AssertionResult r = OrderInBracket(h, e, 4.0, 0.15);
  ASSERT_FALSE(r);
  const std::string msg = r.message();
  for (const char* piece : {"level", "error", "order", "4.00000e-01", "1.00000e-02", "2.0000", "[3.85, 4.15]"})
    EXPECT_NE(msg.find(piece), std::string::npos) << "missing '" << piece << "' in:\n" << msg;
  EXPECT_NONFATAL_FAILURE(ExpectOrderInBracket(h, e, 4.0, 0.15), "2.0000");
}

}  // namespace
}  // namespace tcasim::test_support
