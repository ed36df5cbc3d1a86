// Probes (docs/scenario-format.md "Probes and frames") in both static solvers: a probe at the
// tip is the tip, and an offset turns with the body frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "crosscheck/crosscheck.hpp"
#include "rod/scenario.hpp"

namespace tcasim::crosscheck {
namespace {

using json = nlohmann::json;

/// The same discrete solution evaluated two ways (probe vs tip): round-off relative to L.
constexpr double kRoundOff = 1e-12;
constexpr int kSteps = 64;
constexpr double kNewtonTolerance = 1e-12;

rod::RodModel manipulator_with_probes(double L_fraction_mid) {
  std::ifstream in(std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios" /
                   "circular-manipulator.json");
  json doc = json::parse(in);
  const double L = doc["body"]["length_m"].get<double>();
  doc["probes"] = json::array({
      {{"name", "at_tip"}, {"s_m", L}, {"offset_m", {0.0, 0.0, 0.0}}},
      {{"name", "stalk"}, {"s_m", L}, {"offset_m", {0.001, -0.002, 0.005}}},
      {{"name", "mid"}, {"s_m", L_fraction_mid * L}, {"offset_m", {0.002, 0.0, 0.0}}},
  });
  return rod::parse_scenario(doc);
}

void expect_tip_probes(const rod::Result& r, double L) {
  ASSERT_EQ(r.probes.size(), 3u);
  EXPECT_EQ(r.probes[0].name, "at_tip");
  EXPECT_LT((r.probes[0].position_W_m - r.tip_position_W_m).norm(), kRoundOff * L);
  const Eigen::Vector3d stalk =
      r.tip_position_W_m + r.tip_R_WB * Eigen::Vector3d(0.001, -0.002, 0.005);
  EXPECT_LT((r.probes[1].position_W_m - stalk).norm(), kRoundOff * L);
}

TEST(Probes, AProbeAtTheTipIsTheTipAndItsOffsetTurnsWithTheFrameInBothSolvers) {
  const rod::RodModel m = manipulator_with_probes(0.37);
  const crosscheck::Run s = solve_shooting_rk4(m, kSteps, kNewtonTolerance);
  const crosscheck::Run f = solve_fe(m, FeSettings{});
  ASSERT_TRUE(s.converged && f.converged) << s.status << " / " << f.status;
  expect_tip_probes(s.result, m.length_m);
  expect_tip_probes(f.result, m.length_m);
  // The body has bent: the stalk's offset is not the same vector in the world frame.
  EXPECT_GT((s.result.tip_R_WB - Eigen::Matrix3d::Identity()).norm(), 1e-2);
}

}  // namespace
}  // namespace tcasim::crosscheck
