// Shooting solver with strings anchored inside the body (docs/scenario-format.md "String
// extent"): the closed form of a straight string anchored at s_e < L (and of one over
// [s_a, s_b]) at order four, the sensitivities through the anchor jumps, the global balance,
// and strings over [0, L] given explicitly unchanged.
#include "support/anchored_string.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "cosserat/shooting.hpp"
#include "jacobian_check.hpp"
#include "models.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"
#include "support/convergence.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::cosserat {
namespace {

using test_support::AnchoredString;

Options rk4(int steps) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = 1e-12;
  return o;
}

void expect_closed_form(const AnchoredString& c, const char* what) {
  const rod::RodModel m = rod::parse_scenario(c.scenario());
  const std::vector<int> steps{10, 20, 40, 80};
  std::vector<double> h, err;
  for (int n : steps) {
    const rod::Result r = solve(m, rk4(n));
    ASSERT_TRUE(r.converged) << r.message;
    h.push_back(m.length_m / n);
    err.push_back((r.tip_position_W_m - c.tip_position()).norm());
    if (n == steps.back()) {
      EXPECT_NEAR(r.actuators[0].elongation_m, c.elongation_m(), 1e-9 * m.length_m);
      const double angle = std::atan2(r.tip_R_WB(0, 2), r.tip_R_WB(2, 2));
      EXPECT_NEAR(angle, c.tip_angle(), 1e-7);
    }
  }
  std::printf("%s, RK4 shooting:\n%s", what, test_support::convergence_table(h, err).c_str());
  test_support::ExpectOrderInBracket(h, err, 4.0, 0.5);
  EXPECT_LE(err.back(), 1e-7 * m.length_m);
}

TEST(ShootingAnchoredString, StringEndingInsideTheBodyBendsOnlyItsSpanAtOrderFour) {
  AnchoredString c;  // span [0, 0.06] of L = 0.1
  expect_closed_form(c, "string anchored at 0.6 L");
}

TEST(ShootingAnchoredString, StringBetweenTwoInnerAnchorsBendsOnlyBetweenThem) {
  AnchoredString c;
  c.s_a_m = 0.03;
  c.s_b_m = 0.08;
  expect_closed_form(c, "string over [0.3 L, 0.8 L]");
}

TEST(ShootingAnchoredString, ExplicitFullSpanGivesTheSameNumbersAsNoSpan) {
  AnchoredString c;
  c.s_b_m = c.length_m;
  nlohmann::json j = c.scenario();
  const rod::RodModel with_span = rod::parse_scenario(j);
  j["actuators"][0].erase("span_m");
  const rod::RodModel without = rod::parse_scenario(j);
  EXPECT_FALSE(with_span.has_inner_anchors());
  const rod::Result a = solve(with_span, rk4(32)), b = solve(without, rk4(32));
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_EQ(a.tip_position_W_m, b.tip_position_W_m);
  EXPECT_EQ(a.actuators[0].elongation_m, b.actuators[0].elongation_m);
}

/// Three strings: a TCA from the base to an inner anchor, a tension string between two inner
/// anchors and one from an inner anchor to the tip, on a precurved body with a tip wrench.
rod::RodModel anchored_rod() {
  AnchoredString c;
  nlohmann::json j = c.scenario();
  j["body"]["reference_curvature_1_m"] = {0.0, 2.0, 0.0};
  j["tip_load"]["moment_Nm"] = {2e-4, -1e-4, 0.0};
  rod::RodModel m = rod::parse_scenario(j);
  m.actuators.clear();
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), -0.0025, 0.0005,
                          units::degC_to_K(90.0));
  testing::add_tension_string(m, "mid", 0.002, 0.001, 0.5);
  testing::add_tension_string(m, "tip", 0.0, -0.003, 0.3);
  m.actuators[0].span_m = std::array<double, 2>{0.0, 0.07};
  m.actuators[1].span_m = std::array<double, 2>{0.02, 0.05};
  m.actuators[2].span_m = std::array<double, 2>{0.04, m.length_m};
  for (rod::Actuator& a : m.actuators) {
    a.rest_length_m =
        rod::reference_path(a.routing, m, a.span_start_m(), a.span_end_m(m.length_m)).length_m;
  }
  return m;
}

TEST(ShootingAnchoredString, SensitivityJacobianThroughAnchorJumpsMatchesCentralDifferences) {
  const rod::RodModel m = anchored_rod();
  ASSERT_EQ(m.anchor_points(), (std::vector<double>{0.02, 0.04, 0.05, 0.07}));
  const double worst = testing::sensitivity_vs_central_difference(m, rk4(40));
  std::printf("[jacobian] anchored strings, sensitivity vs central differences: %.2e\n", worst);
  EXPECT_LE(worst, 1e-7);
}

/// The strings of anchored_rod() on spline routings (docs/conventions.md "Spline routings"):
/// the TCA through a `linear` routing with kinks at 0.03 and 0.05, the tip string on a cubic.
rod::RodModel spline_rod() {
  rod::RodModel m = anchored_rod();
  rod::Routing& kinked = m.actuators[0].routing;
  kinked.type = rod::Routing::Type::kSpline;
  kinked.linear = true;
  kinked.knot_s_m = {0.0, 0.03, 0.05, 0.07};
  kinked.knot_offsets_m = {{-0.0025, 0.0005}, {-0.0025, 0.0005}, {-0.001, 0.002}, {0.0, 0.002}};
  kinked.build_spline();
  rod::Routing& cubic = m.actuators[2].routing;
  cubic.type = rod::Routing::Type::kSpline;
  cubic.knot_s_m = {0.04, 0.06, 0.08, m.length_m};
  cubic.knot_offsets_m = {{0.0, -0.003}, {0.001, -0.002}, {0.002, -0.002}, {0.001, 0.0}};
  cubic.build_spline();
  for (rod::Actuator& a : m.actuators) {
    a.rest_length_m =
        rod::reference_path(a.routing, m, a.span_start_m(), a.span_end_m(m.length_m)).length_m;
  }
  return m;
}

TEST(ShootingAnchoredString, SensitivityJacobianThroughSplineKinksMatchesCentralDifferences) {
  const rod::RodModel m = spline_rod();
  ASSERT_EQ(m.routing_kinks(), (std::vector<double>{0.03, 0.05}));
  const double worst = testing::sensitivity_vs_central_difference(m, rk4(40));
  std::printf("[jacobian] spline strings, sensitivity vs central differences: %.2e\n", worst);
  EXPECT_LE(worst, 1e-7);  // as for the anchors above (central differences' own error)
  // The solve converges and balances globally (the kinks' point forces included): the
  // imbalance is RK4's error in the conserved total wrench, falling at order 4.
  std::vector<double> h, imbalance;
  for (const int n : {32, 64, 128}) {
    ShootingSolver solver(m, rk4(n));
    Solution sol;
    const Summary s = solver.solve(rod::Loads::from_model(m), sol);
    ASSERT_TRUE(s.converged()) << s.message;
    h.push_back(m.length_m / n);
    imbalance.push_back(s.force_imbalance_W_N.norm() + s.moment_imbalance_W_Nm.norm() / m.length_m);
  }
  std::printf("spline strings, global imbalance [N]:\n%s",
              test_support::convergence_table(h, imbalance).c_str());
  test_support::ExpectOrderInBracket(h, imbalance, 4.0, 0.5);  // measured 4.20, 4.25
}

TEST(ShootingAnchoredString, AnchoredStringsConvergeAndBalanceGlobally) {
  rod::RodModel m = anchored_rod();
  m.gravity_W_m_s2 = {0.0, -9.81, 0.0};
  m.material.density_profile = rod::Profile(1000);
  ShootingSolver solver(m, rk4(64));
  Solution sol;
  const Summary s = solver.solve(rod::Loads::from_model(m), sol);
  ASSERT_TRUE(s.converged()) << s.message;
  // Only the string from the base loads the base; the others are self-balanced.
  EXPECT_LE(s.force_imbalance_W_N.norm(), 1e-9);
  EXPECT_LE(s.moment_imbalance_W_Nm.norm(), 1e-10);
}

}  // namespace
}  // namespace tcasim::cosserat
