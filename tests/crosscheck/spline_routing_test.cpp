// Spline routings (docs/scenario-format.md "General routing and string extent") in both
// static solvers: a cubic spline through points of a straight string is that string; through
// points of a helix it converges to the helix; a linear routing's kink is the same as two
// strings anchored at the kink; both solvers agree; bad spline input is rejected by key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "cosserat/dynamics.hpp"
#include "crosscheck/crosscheck.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"
#include "support/convergence.hpp"
#include "support/input_error.hpp"

namespace tcasim::crosscheck {
namespace {

using json = nlohmann::json;

constexpr double kL = 0.1;
/// The same discrete problem written two ways: round-off relative to L.
constexpr double kRoundOff = 1e-11;
constexpr int kSteps = 64;  // RK4 steps: a multiple of the pieces (equal steps in both models)
constexpr double kNewtonTolerance = 1e-12;

json body() {
  json j;
  j["schema"] = "tcasim.scenario/1";
  j["name"] = "spline-routing";
  j["body"]["length_m"] = kL;
  j["body"]["section"] = {{"shape", "circle"}, {"diameter_m", 0.010}};
  j["body"]["material"] = {{"youngs_modulus_Pa", 1.0e6}, {"poisson_ratio", 0.5}};
  j["actuators"] = json::array();
  return j;
}

json tension(double T) { return {{"type", "tension"}, {"tension_N", T}}; }

json spline(const std::vector<double>& s, const std::vector<Eigen::Vector2d>& p,
            const char* interpolation = "cubic") {
  json pts = json::array();
  for (const Eigen::Vector2d& x : p) pts.push_back({x.x(), x.y()});
  return {{"type", "spline"}, {"s_m", s}, {"offset_m", pts}, {"interpolation", interpolation}};
}

struct Pair {
  Run shooting, fe;
};

Pair solve_both(const rod::RodModel& m, int steps = kSteps, int elements = 16) {
  FeSettings fe = tight_tolerances();
  fe.elements = elements;
  fe.order = 2;
  Pair p{solve_shooting_rk4(m, steps, kNewtonTolerance), solve_fe(m, fe)};
  EXPECT_TRUE(p.shooting.converged) << p.shooting.status;
  EXPECT_TRUE(p.fe.converged) << p.fe.status;
  return p;
}

TEST(SplineRouting, CubicThroughPointsOfAStraightStringIsTheStraightStringInBothSolvers) {
  json a = body(), b = body();
  const Eigen::Vector2d d(0.003, 0.001);
  a["actuators"].push_back({{"name", "s"},
                            {"routing", {{"type", "straight"}, {"offset_m", {d.x(), d.y()}}}},
                            {"drive", tension(1.5)}});
  b["actuators"].push_back({{"name", "s"},
                            {"routing", spline({0.0, 0.025, 0.05, 0.075, kL}, {d, d, d, d, d})},
                            {"drive", tension(1.5)}});
  const rod::RodModel ma = rod::parse_scenario(a), mb = rod::parse_scenario(b);
  EXPECT_NEAR(mb.actuators[0].rest_length_m, ma.actuators[0].rest_length_m, 1e-15);
  const Pair pa = solve_both(ma), pb = solve_both(mb);
  EXPECT_LT((pa.shooting.result.tip_position_W_m - pb.shooting.result.tip_position_W_m).norm(),
            kRoundOff * kL);
  EXPECT_LT((pa.fe.result.tip_position_W_m - pb.fe.result.tip_position_W_m).norm(), kRoundOff * kL);
  EXPECT_NEAR(pa.shooting.result.actuators[0].elongation_m,
              pb.shooting.result.actuators[0].elongation_m, kRoundOff * kL);
  // The string bends the body (the comparison is not between two straight rods).
  EXPECT_GT(pa.shooting.result.tip_position_W_m.head<2>().norm(), 1e-3 * kL);
}

/// Helix of radius R, 1.25 turns over L, and a cubic spline through k + 1 of its points.
constexpr double kHelixRadius = 0.003, kTurnsPerM = 12.5;
json helix_routing() {
  return {
      {"type", "helix"}, {"radius_m", kHelixRadius}, {"phase_deg", 0}, {"turns_per_m", kTurnsPerM}};
}
json helix_spline(int k) {
  std::vector<double> s;
  std::vector<Eigen::Vector2d> p;
  for (int j = 0; j <= k; ++j) {
    s.push_back(kL * j / k);
    const double t = 2.0 * units::kPi * kTurnsPerM * s.back();
    p.emplace_back(kHelixRadius * std::cos(t), kHelixRadius * std::sin(t));
  }
  return spline(s, p);
}

/// Observed order of the tip error of the spline string against the helix, k = 4 ... 32
/// (measured, both solvers: 3.33, 3.08, 3.02). The natural end conditions r'' = 0, where the
/// helix has |r''| = R (2 pi k)^2, make r wrong by O(h^2) in end layers of width O(h): third
/// order at the tip, below the cubic's fourth order inside.
constexpr double kHelixOrder = 3.0;
constexpr double kHelixOrderTolerance = 0.3;  // from k = 8 on (k = 4 -> 8 is pre-asymptotic)

TEST(SplineRouting, CubicThroughPointsOfAHelixConvergesToTheHelixInBothSolvers) {
  json h = body();
  h["actuators"].push_back({{"name", "s"}, {"routing", helix_routing()}, {"drive", tension(1.0)}});
  constexpr int kFine = 256, kElements = 64;
  const Pair ref = solve_both(rod::parse_scenario(h), kFine, kElements);
  std::vector<double> hs, es, ef;
  for (const int k : {4, 8, 16, 32}) {
    json j = body();
    j["actuators"].push_back(
        {{"name", "s"}, {"routing", helix_spline(k)}, {"drive", tension(1.0)}});
    const Pair p = solve_both(rod::parse_scenario(j), kFine, kElements);
    hs.push_back(kL / k);
    es.push_back(
        (p.shooting.result.tip_position_W_m - ref.shooting.result.tip_position_W_m).norm());
    ef.push_back((p.fe.result.tip_position_W_m - ref.fe.result.tip_position_W_m).norm());
  }
  std::printf("cubic spline vs helix, shooting:\n%s",
              test_support::convergence_table(hs, es).c_str());
  std::printf("cubic spline vs helix, FE:\n%s", test_support::convergence_table(hs, ef).c_str());
  test_support::ExpectOrderInBracket(hs, es, kHelixOrder, kHelixOrderTolerance, 1);
  test_support::ExpectOrderInBracket(hs, ef, kHelixOrder, kHelixOrderTolerance, 1);
}

/// A string at offset d straight to s_k, then straight toward (d2) at the tip: one `linear`
/// routing with a kink at s_k, or two strings anchored at s_k with the same tension.
json kinked(bool as_pieces, double T) {
  json j = body();
  const double sk = 0.05;
  const Eigen::Vector2d d(0.003, 0.0), d2(0.001, 0.001);
  if (!as_pieces) {
    j["actuators"].push_back({{"name", "kinked"},
                              {"routing", spline({0.0, sk, kL}, {d, d, d2}, "linear")},
                              {"drive", tension(T)}});
    return j;
  }
  j["actuators"].push_back({{"name", "before"},
                            {"routing", {{"type", "straight"}, {"offset_m", {d.x(), d.y()}}}},
                            {"span_m", {0.0, sk}},
                            {"drive", tension(T)}});
  j["actuators"].push_back(
      {{"name", "after"}, {"routing", spline({sk, kL}, {d, d2})}, {"drive", tension(T)}});
  return j;
}

TEST(SplineRouting, LinearKinkActsAsTwoStringsAnchoredAtTheKinkInBothSolvers) {
  const rod::RodModel one = rod::parse_scenario(kinked(false, 1.5));
  const rod::RodModel two = rod::parse_scenario(kinked(true, 1.5));
  EXPECT_NEAR(one.actuators[0].rest_length_m,
              two.actuators[0].rest_length_m + two.actuators[1].rest_length_m, 1e-15);
  const Pair a = solve_both(one), b = solve_both(two);
  for (const auto& [x, y] : {std::pair{&a.shooting, &b.shooting}, std::pair{&a.fe, &b.fe}}) {
    EXPECT_LT((x->result.tip_position_W_m - y->result.tip_position_W_m).norm(), kRoundOff * kL);
    EXPECT_LT((x->result.tip_R_WB - y->result.tip_R_WB).norm(), kRoundOff);
    EXPECT_NEAR(x->result.actuators[0].elongation_m,
                y->result.actuators[0].elongation_m + y->result.actuators[1].elongation_m,
                kRoundOff * kL);
  }
}

/// Both solvers on a 3-D spline scenario at fine settings (RK4 512 steps, 128 quadratic
/// elements): measured tip difference 1.5e-11 L, both discretization errors far below; the
/// gate leaves a factor 60 for platform round-off and stays far below the string's effect.
constexpr double kAgreement = 1e-9;

TEST(SplineRouting, BothSolversAgreeOnCubicAndLinearSplines) {
  json j = kinked(false, 1.0);
  j["actuators"].push_back(
      {{"name", "wavy"},
       {"routing", spline({0.0, 0.02, 0.05, 0.07, kL},
                          {Eigen::Vector2d(-0.002, 0.0), Eigen::Vector2d(-0.001, 0.002),
                           Eigen::Vector2d(0.0, 0.003), Eigen::Vector2d(0.001, 0.002),
                           Eigen::Vector2d(0.0, -0.002)})},
       {"span_m", {0.0, 0.09}},
       {"drive", tension(0.8)}});
  const rod::RodModel m = rod::parse_scenario(j);
  const Pair p = solve_both(m, 512, 128);
  const double diff =
      (p.shooting.result.tip_position_W_m - p.fe.result.tip_position_W_m).norm() / kL;
  std::printf("spline scenario: |p_shooting - p_fe| / L = %.3e\n", diff);
  EXPECT_LT(diff, kAgreement);
  EXPECT_GT(p.shooting.result.tip_position_W_m.head<2>().norm(), 1e-2 * kL);
}

// --- Input errors ----------------------------------------------------------------------

json with_routing(const json& routing, const json& span = nullptr) {
  json j = body();
  json a = {{"name", "s"}, {"routing", routing}, {"drive", tension(1.0)}};
  if (!span.is_null()) a["span_m"] = span;
  j["actuators"].push_back(a);
  return j;
}

void expect_error(const json& routing, const std::string& key, const std::string& rule,
                  const json& span = nullptr) {
  SCOPED_TRACE(routing.dump());
  test_support::expect_input_error([&] { (void)rod::parse_scenario(with_routing(routing, span)); },
                                   key, rule);
}

TEST(SplineRouting, BadSplineInputIsRejectedNamingKeyAndRule) {
  const Eigen::Vector2d a(0.001, 0.0), b(0.002, 0.0), c(0.0, 0.001);
  const std::string r = "actuators[0].routing";
  expect_error(spline({0.0, 0.05, 0.05}, {a, b, c}), r + ".s_m[2]", "strictly increasing");
  expect_error(spline({0.0, 0.06, 0.05}, {a, b, c}), r + ".s_m[2]", "strictly increasing");
  expect_error(spline({0.0}, {a}), r + ".s_m", "at least two");
  expect_error(spline({0.0, 0.05, kL}, {a, b}), r + ".offset_m", "one per entry of s_m");
  expect_error(spline({0.0, 0.05, 0.2}, {a, b, c}), r + ".s_m[2]", "inside the body");
  expect_error(spline({-0.01, 0.05, kL}, {a, b, c}), r + ".s_m[0]", "inside the body");
  expect_error(spline({0.0, 0.05, kL}, {a, Eigen::Vector2d(0.006, 0.0), c}), r + ".offset_m[1]",
               "outside the body section");
  // Knots inside, the cubic between them outside (it overshoots toward the edge).
  expect_error(
      spline({0.0, 0.01, 0.02, kL}, {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.0049, 0.0),
                                     Eigen::Vector2d(0.0049, 0.0), Eigen::Vector2d(0.0, 0.0)}),
      r + ".offset_m", "outside the body section");
  json bad = spline({0.0, kL}, {a, b});
  bad["interpolation"] = "quadratic";
  expect_error(bad, r + ".interpolation", "must be one of");
  bad = spline({0.0, kL}, {a, b});
  bad["offset_m"][1] = {0.001, 0.0, 0.0};
  expect_error(bad, r + ".offset_m[1]", "2 numbers");
  bad = spline({0.0, kL}, {a, b});
  bad["radius_m"] = 0.001;
  expect_error(bad, r + ".radius_m", "");
  expect_error(spline({0.02, 0.08}, {a, b}), "actuators[0].span_m", "inside the spline",
               json::array({0.01, 0.08}));
  // A kink on a precurved body where the string folds back (e3 . q* <= 0 on one side).
  json folded =
      with_routing(spline({0.0, 0.05, kL}, {a, Eigen::Vector2d(0.004, 0.0), a}, "linear"));
  folded["body"]["reference_curvature_1_m"] = {0.0, 300.0, 0.0};
  test_support::expect_input_error([&] { (void)rod::parse_scenario(folded); }, r + ".offset_m",
                                   "fold");
}

TEST(SplineRouting, SpanDefaultsToTheKnotsAndTheCubicThroughTwoPointsIsTheLine) {
  const rod::RodModel m = rod::parse_scenario(with_routing(
      spline({0.02, 0.08}, {Eigen::Vector2d(0.001, 0.0), Eigen::Vector2d(0.003, 0.0)})));
  EXPECT_DOUBLE_EQ(m.actuators[0].span_start_m(), 0.02);
  EXPECT_DOUBLE_EQ(m.actuators[0].span_end_m(kL), 0.08);
  const rod::Routing& ro = m.actuators[0].routing;
  EXPECT_NEAR(ro.r(0.05).x(), 0.002, 1e-18);
  EXPECT_NEAR(ro.dr(0.05).x(), 0.002 / 0.06, 1e-15);
  EXPECT_EQ(ro.ddr(0.05).norm(), 0.0);
  // Rest length: the straight segment's length.
  EXPECT_NEAR(m.actuators[0].rest_length_m, std::hypot(0.06, 0.002), 1e-15);
}

/// Central differences with step 1e-6 m: truncation h^2 r'''/6 ~ 2e-11 (r''' ~ 1e2 1/m^2),
/// round-off eps |r| / h ~ 2e-13 for r'; for r'' (the cubic's r'''' = 0) round-off
/// eps |r'| / h ~ 1e-11 and the jump of r''' only at the points, away from the samples.
constexpr double kFdStep = 1e-6, kFdTolerance1 = 1e-9, kFdTolerance2 = 1e-8;

TEST(SplineRouting, DerivativesMatchCentralDifferencesAndTheCubicIsC2AtItsPoints) {
  for (const char* interpolation : {"cubic", "linear"}) {
    SCOPED_TRACE(interpolation);
    const rod::RodModel m = rod::parse_scenario(with_routing(spline(
        {0.0, 0.02, 0.05, 0.07, kL},
        {Eigen::Vector2d(-0.002, 0.0), Eigen::Vector2d(-0.001, 0.002), Eigen::Vector2d(0.0, 0.003),
         Eigen::Vector2d(0.001, 0.002), Eigen::Vector2d(0.0, -0.002)},
        interpolation)));
    const rod::Routing& ro = m.actuators[0].routing;
    for (const double s : {0.004, 0.031, 0.066, 0.093}) {  // inside pieces
      const Eigen::Vector3d fd1 = (ro.r(s + kFdStep) - ro.r(s - kFdStep)) / (2.0 * kFdStep);
      const Eigen::Vector3d fd2 = (ro.dr(s + kFdStep) - ro.dr(s - kFdStep)) / (2.0 * kFdStep);
      EXPECT_LT((ro.dr(s) - fd1).norm(), kFdTolerance1) << s;
      EXPECT_LT((ro.ddr(s) - fd2).norm(), kFdTolerance2) << s;
    }
    for (std::size_t j = 0; j < ro.knot_s_m.size(); ++j) {
      const double s = ro.knot_s_m[j];
      using rod::Side;
      EXPECT_NEAR((ro.r(s, Side::kLeft) - ro.r(s, Side::kRight)).norm(), 0.0, 1e-18);
      EXPECT_NEAR(ro.r(s).x(), m.actuators[0].routing.knot_offsets_m[j].x(), 1e-18);
      const double jump = (ro.dr(s, Side::kLeft) - ro.dr(s, Side::kRight)).norm();
      const bool interior = j > 0 && j + 1 < ro.knot_s_m.size();
      if (ro.linear && interior) {
        EXPECT_GT(jump, 1e-2) << s;  // a kink
      } else {
        EXPECT_LT(jump, 1e-13) << s;
        EXPECT_LT((ro.ddr(s, Side::kLeft) - ro.ddr(s, Side::kRight)).norm(), 1e-9) << s;
      }
    }
    if (!ro.linear) {  // natural end conditions
      EXPECT_LT(ro.ddr(0.0).norm(), 1e-12);
      EXPECT_LT(ro.ddr(kL, rod::Side::kLeft).norm(), 1e-12);
    }
  }
}

// The shooting dynamics takes spline routings: one through points of a straight path (a knot
// at L / 2, a grid node) moves exactly as the straight routing, to round-off, when gravity is
// switched on at t = 0+.
TEST(SplineRouting, ShootingDynamicsOfASplineThroughAStraightPathIsTheStraightRouting) {
  Eigen::Vector3d tips[2];
  for (const bool as_spline : {false, true}) {
    json j = body();
    j["body"]["material"]["density_kg_m3"] = 1100.0;
    const Eigen::Vector2d r(0.002, 0.001);
    j["actuators"].push_back(
        {{"name", "t"},
         {"routing", as_spline ? spline({0.0, 0.5 * kL, kL}, {r, r, r})
                               : json{{"type", "straight"}, {"offset_m", {r.x(), r.y()}}}},
         {"drive", tension(0.05)}});
    const rod::RodModel m = rod::parse_scenario(j);
    cosserat::DynamicsOptions o;
    o.steps = 20;
    o.dt_s = 1e-3;
    o.tolerance = kNewtonTolerance;
    cosserat::RodDynamics d(m, o);
    rod::Loads loads = rod::Loads::from_model(m);
    ASSERT_TRUE(d.initialize(loads).converged());
    loads.gravity_W_m_s2 = Eigen::Vector3d(-9.81, 0.0, 0.0);
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(d.step(loads).converged());
    tips[as_spline ? 1 : 0] = d.tip_position_W_m();
  }
  EXPECT_GT((tips[0] - Eigen::Vector3d(0.0, 0.0, kL)).norm(), 1e-5);  // it moves
  EXPECT_LT((tips[1] - tips[0]).norm(), kRoundOff * kL);
}

}  // namespace
}  // namespace tcasim::crosscheck
