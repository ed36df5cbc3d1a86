// Probes (docs/scenario-format.md "Probes and frames") in both static solvers: a probe at the
// tip is the tip, and an offset turns with the body frame.
#include <gtest/gtest.h>

#include <cmath>
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

// Where the FE puts no node at a probe (it never does: a probe changes no other number), the
// probe is the element interpolation, which converges more slowly than the nodes: quadratic
// elements give the nodal positions to O(h^4) (the tip, a probe at a node) but positions
// between nodes only to O(h^3), the interpolation's own order (docs/scenario-format.md
// "Probes and frames"). Measured on this rod, error / L at s = 0.37 L: 4.1e-6, 7.2e-7,
// 7.6e-8 at 16, 32, 64 elements (mean order 2.87; it scatters with where s falls inside its
// element), against 3.7e-7, 2.3e-8, 1.4e-9 at s = L / 2 (a node; order 4.00).
TEST(Probes, FeProbesBetweenNodesConvergeAtTheInterpolationOrderAndAtNodesAtTheNodalOrder) {
  rod::RodModel m = manipulator_with_probes(0.37);
  m.probes.push_back({"node", 0.5 * m.length_m, Eigen::Vector3d::Zero()});
  const double L = m.length_m;
  const crosscheck::Run ref = solve_shooting_rk4(m, 1024, kNewtonTolerance);
  ASSERT_TRUE(ref.converged) << ref.status;
  std::vector<double> between, at_node;
  for (const int elements : {16, 32, 64}) {
    FeSettings fe;
    fe.elements = elements;
    fe.order = 2;
    const crosscheck::Run f = solve_fe(m, fe);
    ASSERT_TRUE(f.converged) << f.status;
    ASSERT_EQ(f.result.probes.size(), 4u);
    between.push_back((f.result.probes[2].position_W_m - ref.result.probes[2].position_W_m).norm() /
                      L);
    at_node.push_back((f.result.probes[3].position_W_m - ref.result.probes[3].position_W_m).norm() /
                      L);
  }
  const double order_between = std::log2(between[0] / between[2]) / 2.0;
  const double order_at_node = std::log2(at_node[0] / at_node[1]);
  EXPECT_GT(order_between, 2.4) << between[0] << " " << between[1] << " " << between[2];
  EXPECT_LT(order_between, 3.4) << between[0] << " " << between[1] << " " << between[2];
  EXPECT_NEAR(order_at_node, 4.0, 0.2) << at_node[0] << " " << at_node[1];
  // Between nodes the error is the interpolation's, well above the nodal one at every mesh.
  for (std::size_t k = 0; k < between.size(); ++k) EXPECT_GT(between[k], 5.0 * at_node[k]);
}

}  // namespace
}  // namespace tcasim::crosscheck
