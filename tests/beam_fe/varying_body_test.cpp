// Beam FE on bodies whose section varies along s (docs/scenario-format.md "Profiles along the
// body"): the end-moment cantilever's closed forms (tapered, and stepped on the mesh aligned to
// the step: orders 2 and 4), and a loaded, stepped, tapered, precurved rod against the
// shooting solver.
#include "support/varying_body.hpp"

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

using test_support::MomentCantilever;

Options fe(int elements, int order) {
  Options o;
  o.elements = elements;
  o.order = order;
  o.tolerance_rel = 1e-12;
  return o;
}

Eigen::Vector3d fe_tip(const rod::RodModel& m, const Options& o, int* elements = nullptr) {
  const testing::Solved s = testing::run(m, o);
  EXPECT_TRUE(s.summary.converged()) << s.summary.message;
  if (elements) *elements = static_cast<int>(s.state.s_m.size() - 1) / o.order;
  return s.state.p_W_m.back();
}

TEST(BeamFeVaryingBody, TaperedCantileverUnderEndMomentConvergesAtOrderTwoAndFour) {
  const MomentCantilever c;
  const rod::RodModel m = rod::parse_scenario(c.tapered());
  const Eigen::Vector3d exact = c.tapered_tip();
  for (const int order : {1, 2}) {
    const std::vector<int> meshes =
        order == 1 ? std::vector<int>{8, 16, 32, 64} : std::vector<int>{4, 8, 16, 32};
    std::vector<double> h, err;
    for (int n : meshes) {
      h.push_back(c.length_m / n);
      err.push_back((fe_tip(m, fe(n, order)) - exact).norm());
    }
    std::printf("tapered cantilever, FE order %d:\n%s", order,
                test_support::convergence_table(h, err).c_str());
    test_support::ExpectOrderInBracket(h, err, order == 1 ? 2.0 : 4.0, 0.5);
  }
}

TEST(BeamFeVaryingBody, SteppedSectionConvergesAtOrderTwoAndFourOnTheMeshAlignedToTheStep) {
  // The mesh has a node at the step (0.4 L): 0.4 n and 0.6 n elements on the two pieces, so
  // n = 5, 10, 20, 40 are nested uniform refinements of each piece.
  const MomentCantilever c;
  const rod::RodModel m = rod::parse_scenario(c.stepped());
  const Eigen::Vector3d exact = c.stepped_tip();
  for (const int order : {1, 2}) {
    const std::vector<int> meshes =
        order == 1 ? std::vector<int>{5, 10, 20, 40} : std::vector<int>{5, 10, 20};
    std::vector<double> h, err;
    for (const int n : meshes) {
      int elements = 0;
      err.push_back((fe_tip(m, fe(n, order), &elements) - exact).norm());
      EXPECT_EQ(elements, n);  // round(0.4 n) + round(0.6 n)
      h.push_back(c.length_m / elements);
    }
    std::printf("stepped section, FE order %d (aligned mesh):\n%s", order,
                test_support::convergence_table(h, err).c_str());
    test_support::ExpectOrderInBracket(h, err, order == 1 ? 2.0 : 4.0, 0.5);
  }
}

/// The loaded varying body (test_support::loaded_varying_body) with a tension string and a
/// helical one (the jumps carry loaded strings), and gravity on a varying density.
rod::RodModel loaded_varying_rod() {
  const double length_m = MomentCantilever{}.length_m;
  nlohmann::json j = test_support::loaded_varying_body();
  j["body"]["material"]["density_kg_m3"] = {{"s_m", {0.0, 0.05, 0.05, length_m}},
                                            {"values", {1000, 1000, 2000, 1500}}};
  j["gravity_m_s2"] = {0.0, 0.0, -9.81};
  j["actuators"] = nlohmann::json::parse(R"([
    {"name": "t", "routing": {"type": "straight", "offset_m": [0.002, 0.001]},
     "drive": {"type": "tension", "tension_N": 0.2}},
    {"name": "h", "routing": {"type": "helix", "radius_m": 0.0025, "turns_per_m": 5.0},
     "drive": {"type": "tension", "tension_N": 0.1}}])");
  return rod::parse_scenario(j);
}

TEST(BeamFeVaryingBody, LoadedVaryingBodyAgreesWithTheShootingSolver) {
  const rod::RodModel m = loaded_varying_rod();
  cosserat::Options so;
  so.integrator.steps = 256;
  so.tolerance = 1e-12;
  const rod::Result shoot = cosserat::solve(m, so);
  ASSERT_TRUE(shoot.converged) << shoot.message;
  const testing::Solved s = testing::run(m, fe(64, 2));
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  const double gap = (s.state.p_W_m.back() - shoot.tip_position_W_m).norm();
  const double angle =
      Eigen::AngleAxisd(s.state.q_WB.back().toRotationMatrix().transpose() * shoot.tip_R_WB)
          .angle();
  std::printf("loaded varying rod: FE (64 quadratic) vs shooting (256 RK4): tip %.2e m, %.2e rad\n",
              gap, angle);
  EXPECT_LE(gap, 1e-8 * m.length_m);
  EXPECT_LE(angle, 1e-7);
  const rod::Result fr = make_result(m, fe(64, 2), s.state, s.summary);
  ASSERT_EQ(fr.actuators.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(fr.actuators[i].elongation_m, shoot.actuators[i].elongation_m, 1e-10);
  }
}

}  // namespace
}  // namespace tcasim::beam_fe
