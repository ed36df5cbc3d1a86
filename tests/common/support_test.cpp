// Tests of the test helpers themselves: finite differences and observed orders.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "support/convergence.hpp"
#include "support/elastica.hpp"
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
  const auto f = [](const Eigen::VectorXd& v) {
    return std::exp(v[0]) * std::sin(v[1]) + v[2] * v[2];
  };
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
  for (const char* piece :
       {"level", "error", "order", "4.00000e-01", "1.00000e-02", "2.0000", "[3.85, 4.15]"})
    EXPECT_NE(msg.find(piece), std::string::npos) << "missing '" << piece << "' in:\n" << msg;
  EXPECT_NONFATAL_FAILURE(ExpectOrderInBracket(h, e, 4.0, 0.15), "2.0000");
}

// Carlson's reference values (Numer. Algorithms 10:13-26, 1995, Sec. 3, 14 digits) and
// K(1/2), E(1/2) (DLMF 19.6, 16 digits): the duplication and series give them to round-off.
constexpr double kEllipticRelative = 1e-13;

TEST(SupportElliptic, CarlsonIntegralsMatchCarlsonsTestValues) {
  EXPECT_NEAR(carlson_rf(1.0, 2.0, 0.0), 1.3110287771461, kEllipticRelative * 1.32);
  EXPECT_NEAR(carlson_rf(2.0, 3.0, 4.0), 0.58408284167715, kEllipticRelative);
  EXPECT_NEAR(carlson_rd(0.0, 2.0, 1.0), 1.7972103521034, kEllipticRelative * 1.8);
  EXPECT_NEAR(carlson_rd(2.0, 3.0, 4.0), 0.16510527294261, kEllipticRelative);
  EXPECT_THROW(carlson_rf(-1.0, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(carlson_rd(1.0, 1.0, 0.0), std::invalid_argument);
}

TEST(SupportElliptic, CompleteIntegralsAtParameterOneHalf) {
  const double half_pi = 1.5707963267948966;
  EXPECT_NEAR(elliptic_f(half_pi, 0.5), 1.8540746773013719, kEllipticRelative * 1.9);
  EXPECT_NEAR(elliptic_e(half_pi, 0.5), 1.3506438810476755, kEllipticRelative * 1.4);
  EXPECT_NEAR(elliptic_e(half_pi, 0.0), half_pi, kEllipticRelative * 1.6);
}

/// [Mattiasson1981]'s table has 5 decimals: the closed form rounds to it (half a unit).
constexpr double kTableRounding = 5e-6;

TEST(SupportElliptic, CantileverElasticaReproducesMattiassonsTable) {
  struct Row {
    double k, w, u, rotation;
  };
  for (const Row& row : {Row{1, 0.30172, 0.05643, 0.46135}, Row{2, 0.49346, 0.16064, NAN},
                         Row{5, 0.71379, 0.38763, NAN}, Row{10, 0.81061, 0.55500, 1.43029}}) {
    const ElasticaTip t = cantilever_elastica_tip(row.k);
    EXPECT_NEAR(t.deflection, row.w, kTableRounding) << "k = " << row.k;
    EXPECT_NEAR(1.0 - t.axial, row.u, kTableRounding) << "k = " << row.k;
    if (std::isfinite(row.rotation)) {
      EXPECT_NEAR(t.rotation, row.rotation, kTableRounding) << "k = " << row.k;
    }
  }
  EXPECT_THROW(cantilever_elastica_tip(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace tcasim::test_support
