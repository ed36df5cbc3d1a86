// Beam FE with strings anchored inside the body (docs/scenario-format.md "String extent"):
// nodes at the anchors, the string potential over its span only; the closed form of a
// straight string anchored at s_e < L at orders 2 (linear) and 4 (quadratic) on the aligned
// mesh, and the shooting solver on several anchored strings on a precurved body.
#include "support/anchored_string.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "cosserat/shooting.hpp"
#include "models.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"
#include "support/convergence.hpp"

namespace tcasim::beam_fe {
namespace {

using test_support::AnchoredString;

Options fe(int elements, int order) {
  Options o;
  o.elements = elements;
  o.order = order;
  o.tolerance_rel = 1e-12;
  return o;
}

void expect_orders(const AnchoredString& c, const std::vector<int>& meshes, const char* what) {
  const rod::RodModel m = rod::parse_scenario(c.scenario());
  for (const int order : {1, 2}) {
    std::vector<double> h, err;
    for (const int n : meshes) {
      const testing::Solved s = testing::run(m, fe(n, order));
      ASSERT_TRUE(s.summary.converged()) << s.summary.message;
      const int elements = static_cast<int>(s.state.s_m.size() - 1) / order;
      EXPECT_EQ(elements, n);  // the anchors split n into nested uniform pieces
      h.push_back(c.length_m / elements);
      err.push_back((s.state.p_W_m.back() - c.tip_position()).norm());
    }
    std::printf("%s, FE order %d (aligned mesh):\n%s", what, order,
                test_support::convergence_table(h, err).c_str());
    test_support::ExpectOrderInBracket(h, err, order == 1 ? 2.0 : 4.0, 0.5);
  }
}

TEST(BeamFeAnchoredString, StringEndingInsideTheBodyConvergesAtOrderTwoAndFour) {
  AnchoredString c;  // anchor at 0.6 L: 0.6 n and 0.4 n elements
  expect_orders(c, {5, 10, 20, 40}, "string anchored at 0.6 L");
}

TEST(BeamFeAnchoredString, StringBetweenInnerAnchorsConvergesAtOrderTwoAndFour) {
  AnchoredString c;
  c.s_a_m = 0.02;
  c.s_b_m = 0.08;  // pieces 0.2, 0.6, 0.2 of L
  expect_orders(c, {5, 10, 20, 40}, "string over [0.2 L, 0.8 L]");
}

TEST(BeamFeAnchoredString, MatchesTheShootingSolverOnAnchoredStringsOfAPrecurvedBody) {
  AnchoredString c;
  nlohmann::json j = c.scenario();
  j["body"]["reference_curvature_1_m"] = {0.0, 2.0, 0.0};
  j["tip_load"]["moment_Nm"] = {2e-4, -1e-4, 0.0};
  j["gravity_m_s2"] = {0.0, -9.81, 0.0};
  j["body"]["material"]["density_kg_m3"] = 1000;
  rod::RodModel m = rod::parse_scenario(j);
  m.actuators.clear();
  testing::add_tension_string(m, "base", -0.0025, 0.0005, 0.8);
  testing::add_tension_string(m, "mid", 0.002, 0.001, 0.5);
  testing::add_tension_string(m, "tip", 0.0, -0.003, 0.3);
  m.actuators[0].span_m = std::array<double, 2>{0.0, 0.07};
  m.actuators[1].span_m = std::array<double, 2>{0.02, 0.05};
  m.actuators[2].span_m = std::array<double, 2>{0.04, m.length_m};
  for (rod::Actuator& a : m.actuators) {
    a.rest_length_m =
        rod::reference_path(a.routing, m, a.span_start_m(), a.span_end_m(m.length_m)).length_m;
  }
  cosserat::Options so;
  so.integrator.method = ode::Method::kRk4;
  so.integrator.steps = 200;
  so.tolerance = 1e-12;
  const rod::Result ref = cosserat::solve(m, so);
  ASSERT_TRUE(ref.converged) << ref.message;
  const testing::Solved s = testing::run(m, fe(50, 2));
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  const double diff = (s.state.p_W_m.back() - ref.tip_position_W_m).norm();
  std::printf("anchored strings, FE (50 quadratic) vs shooting (RK4, 200 steps): %.2e m\n", diff);
  EXPECT_LE(diff, 1e-8 * m.length_m);
}

}  // namespace
}  // namespace tcasim::beam_fe
