// ShootingSolver::make_result takes the samples of a solution from the solve's own IVP when
// the solver's memo holds that IVP (the accepted point's samples, recorded on the fine level),
// and integrates it again otherwise. Both must give the same result bit for bit: the same IVP
// with the same observer. A solver that never solved (no memo) always integrates, so its
// result is the reference here. Cases: the planar manipulator through a warm sweep with
// probes, the same in 3-D, the hanging tapered tentacle (pieces, a cold start through the
// homotopy in omega*), and results asked for other loads or another solution than the memo's.
#include <gtest/gtest.h>

#include <string>

#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"
#include "rod/scenario.hpp"
#include "support/varying_body.hpp"

namespace tcasim::cosserat {
namespace {

void expect_same_result(const rod::Result& a, const rod::Result& b, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(a.converged) << a.message;
  ASSERT_TRUE(b.converged) << b.message;
  EXPECT_EQ(a.centerline_s_m, b.centerline_s_m);
  EXPECT_EQ(a.centerline_p_W_m, b.centerline_p_W_m);
  EXPECT_EQ(a.centerline_R_WB, b.centerline_R_WB);
  EXPECT_EQ(a.tip_position_W_m, b.tip_position_W_m);
  EXPECT_EQ(a.tip_R_WB, b.tip_R_WB);
  EXPECT_EQ(a.bending_radius_m, b.bending_radius_m);
  ASSERT_EQ(a.probes.size(), b.probes.size());
  for (std::size_t k = 0; k < a.probes.size(); ++k) {
    EXPECT_EQ(a.probes[k].position_W_m, b.probes[k].position_W_m) << a.probes[k].name;
  }
  ASSERT_EQ(a.actuators.size(), b.actuators.size());
  for (std::size_t i = 0; i < a.actuators.size(); ++i) {
    EXPECT_EQ(a.actuators[i].tension_N, b.actuators[i].tension_N);
    EXPECT_EQ(a.actuators[i].elongation_m, b.actuators[i].elongation_m);
  }
}

Options rk4(int steps, bool planar) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.planar_reduction = planar;
  return o;
}

void sweep_manipulator(bool planar) {
  rod::RodModel m = testing::circular_manipulator(units::degC_to_K(25.0));
  m.probes = {{"mid", 0.5 * m.length_m, {0.001, 0.0, 0.0}},
              {"between", 0.37 * m.length_m, {-0.002, 0.0, 0.001}}};
  const Options o = rk4(32, planar);
  ShootingSolver solver(m, o);
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  for (int t = 25; t <= 150; t += 25) {
    act.set_temperature_K(0, units::degC_to_K(t));
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << s.message;
    ASSERT_EQ(s.planar, planar);
    ShootingSolver fresh(m, o);
    const std::string what = std::to_string(t) + " degC" + (planar ? "" : ", 3-D");
    expect_same_result(solver.make_result(act, sol, s), fresh.make_result(act, sol, s), what);
    // Asked twice, and for the same unknowns under another gravity (not the memo's IVP).
    expect_same_result(solver.make_result(act, sol, s), fresh.make_result(act, sol, s),
                       what + ", again");
    rod::Loads heavier = act;
    heavier.gravity_W_m_s2 *= 1.5;
    expect_same_result(solver.make_result(heavier, sol, s), fresh.make_result(heavier, sol, s),
                       what + ", other gravity");
  }
}

TEST(ResultSamples, PlanarSweepMatchesAFreshSampling) { sweep_manipulator(true); }

TEST(ResultSamples, ThreeDimensionalSweepMatchesAFreshSampling) { sweep_manipulator(false); }

TEST(ResultSamples, VaryingBodyThroughTheHomotopyMatchesAFreshSampling) {
  const rod::RodModel m = rod::parse_scenario(test_support::hanging_tentacle(true));
  const Options o = rk4(40, true);
  ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  ShootingSolver fresh(m, o);
  expect_same_result(solver.make_result(act, sol, s), fresh.make_result(act, sol, s),
                     "tapered tentacle");
}

TEST(ResultSamples, AnotherSolutionThanTheMemosIsIntegrated) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const Options o = rk4(32, true);
  ShootingSolver a(m, o), b(m, o);
  rod::Loads hot = rod::Loads::from_model(m), warm = hot;
  warm.set_temperature_K(0, units::degC_to_K(60.0));
  Solution sa, sb;
  const Summary s_hot = a.solve(hot, sa);
  const Summary s_warm = b.solve(warm, sb);
  ASSERT_TRUE(s_hot.converged() && s_warm.converged());
  // a's memo holds the 90 degC solution; the 60 degC one must be integrated, not replayed.
  ShootingSolver fresh(m, o);
  expect_same_result(a.make_result(warm, sb, s_warm), fresh.make_result(warm, sb, s_warm),
                     "b's solution through a");
  expect_same_result(a.make_result(hot, sa, s_hot), fresh.make_result(hot, sa, s_hot),
                     "a's own solution after it");
}

}  // namespace
}  // namespace tcasim::cosserat
