// Shooting solver on bodies whose section varies along s (docs/scenario-format.md "Profiles
// along the body"): closed forms of the end-moment cantilever (tapered, stepped), their
// observed order, the sensitivities through a jump, uniform bodies unchanged, and the cold
// start's homotopy in the reference curvature's variation.
#include "support/varying_body.hpp"

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

using test_support::MomentCantilever;

Options rk4(int steps) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = 1e-12;
  return o;
}

Eigen::Vector3d shooting_tip(const rod::RodModel& m, const Options& o) {
  const rod::Result r = solve(m, o);
  EXPECT_TRUE(r.converged) << r.message;
  return r.tip_position_W_m;
}

/// Tip errors at 8, 16, 32, 64 steps against the closed form, and the order gate (RK4: 4).
void expect_order_four(const rod::RodModel& m, const Eigen::Vector3d& exact, const char* what) {
  const std::vector<int> steps{8, 16, 32, 64};
  std::vector<double> h, err;
  for (int n : steps) {
    h.push_back(m.length_m / n);
    err.push_back((shooting_tip(m, rk4(n)) - exact).norm());
  }
  std::printf("%s, RK4 shooting:\n%s", what, test_support::convergence_table(h, err).c_str());
  test_support::ExpectOrderInBracket(h, err, 4.0, 0.5);
  // RK4 at h = L/64 on curvatures of about 10/L: below 1e-7 L.
  EXPECT_LE(err.back(), 1e-7 * m.length_m);
}

TEST(ShootingVaryingBody, TaperedCantileverUnderEndMomentMatchesTheClosedFormAtOrderFour) {
  const MomentCantilever c;
  const rod::RodModel m = rod::parse_scenario(c.tapered());
  ASSERT_FALSE(m.uniform_body());
  expect_order_four(m, c.tapered_tip(), "tapered cantilever, end moment");
}

TEST(ShootingVaryingBody, SteppedSectionUnderEndMomentMatchesTheClosedFormAtOrderFour) {
  const MomentCantilever c;
  const rod::RodModel m = rod::parse_scenario(c.stepped());
  ASSERT_EQ(m.breakpoints(), std::vector<double>{c.step_s_m});
  ASSERT_TRUE(m.jumps_at(c.step_s_m));
  expect_order_four(m, c.stepped_tip(), "stepped section, end moment");
  // The curvature jumps by the stiffness ratio (d0/d1)^4 = 16 at the step: the tip rotation
  // is theta(L) to the discretization error (1.1e-7 rad at 64 steps).
  const rod::Result r = solve(m, rk4(64));
  const double theta_tip = std::atan2(r.tip_R_WB(2, 1), r.tip_R_WB(1, 1));
  EXPECT_NEAR(theta_tip, c.stepped_theta(c.length_m), 1e-6);
}

TEST(ShootingVaryingBody, ConstantProfilesGiveTheUniformBodysNumbers) {
  // A profile whose values are all equal is a varying body to the solver (pieces, jumps
  // that do nothing): it must give the uniform body's tip to the discretization error of
  // the split steps, and the uniform file must be uniform.
  MomentCantilever c;
  const rod::RodModel uniform =
      rod::parse_scenario(c.scenario({0.0, c.length_m}, {c.d0_m, c.d0_m}));
  nlohmann::json j = c.tapered();
  j["body"]["section"]["diameter_m"] = c.d0_m;
  const rod::RodModel plain = rod::parse_scenario(j);
  EXPECT_TRUE(plain.uniform_body());
  EXPECT_FALSE(uniform.uniform_body());
  const double theta = 64.0 * c.moment_Nm / (units::kPi * c.E_Pa * std::pow(c.d0_m, 4));
  const Eigen::Vector3d exact =
      test_support::planar_tip_position([&](double s) { return theta * s; }, {0.0, c.length_m});
  EXPECT_LE((shooting_tip(plain, rk4(64)) - exact).norm(), 1e-9 * c.length_m);
  EXPECT_LE((shooting_tip(uniform, rk4(64)) - exact).norm(), 1e-9 * c.length_m);
}

/// The loaded varying body (test_support::loaded_varying_body) with a TCA and a tension
/// string: the jumps carry loaded strings.
rod::RodModel loaded_varying_rod() {
  rod::RodModel m = rod::parse_scenario(test_support::loaded_varying_body());
  testing::add_tension_string(m, "t", 0.002, 0.001, 0.05);
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), -0.0025, 0.0005,
                          units::degC_to_K(90.0));
  // The rest lengths on the precurved part (the helpers assume a straight body).
  for (rod::Actuator& a : m.actuators) a.rest_length_m = rod::reference_path(a.routing, m).length_m;
  return m;
}

TEST(ShootingVaryingBody, SensitivityJacobianThroughLoadedJumpsMatchesCentralDifferences) {
  const rod::RodModel m = loaded_varying_rod();
  const double worst = testing::sensitivity_vs_central_difference(m, rk4(40));
  std::printf("[jacobian] varying body, sensitivity vs central differences: %.2e\n", worst);
  EXPECT_LE(worst, 1e-7);
}

TEST(ShootingVaryingBody, SensitivityJacobianThroughCurvatureAndSectionJumpsWithGravity) {
  // bench/bench_varying_body's tentacle (soft, hanging under its weight, two loaded
  // tendons) with a jump of the reference curvature at L/2 and a stepped diameter at 0.15 m:
  // the sensitivity Jacobian against central differences at the solution and at points
  // away from it (where Newton iterates from a cold guess).
  const rod::RodModel m = rod::parse_scenario(nlohmann::json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "jumps",
    "body": {"length_m": 0.2,
             "section": {"shape": "circle", "diameter_m": {"s_m": [0, 0.15, 0.15, 0.2],
                                                          "values": [0.02, 0.0125, 0.01, 0.01]}},
             "material": {"youngs_modulus_Pa": 69e3, "poisson_ratio": 0.5,
                          "density_kg_m3": 1070},
             "reference_curvature_1_m": [{"s_m": [0, 0.1, 0.1, 0.2], "values": [0, 0, -2, -2]},
                                         0, 0]},
    "base": {"rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]]},
    "gravity_m_s2": [0, 0, -9.80665],
    "actuators": [
      {"name": "tx", "routing": {"type": "straight", "offset_m": [0.003, 0.0]},
       "drive": {"type": "tension", "tension_N": 0.05}},
      {"name": "ty", "routing": {"type": "straight", "offset_m": [0.0, 0.003]},
       "drive": {"type": "tension", "tension_N": 0.02}}]})"));
  ASSERT_TRUE(m.jumps_at(0.1));
  ASSERT_TRUE(m.jumps_at(0.15));
  Options o = rk4(40);
  ShootingSolver sens(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  ASSERT_TRUE(sens.solve(act, sol).converged());
  o.jacobian = JacobianMethod::kCentralDifference;
  ShootingSolver cen(m, o);
  for (double t : {0.0, 0.3, 1.0, 3.0}) {
    Eigen::VectorXd x = sol.unknowns;
    x[0] += t * 1e-4;
    x[3] -= t * 0.03;
    x[4] += t * 0.003;
    x[5] += t * 0.01;
    Eigen::MatrixXd Js, Jc;
    ASSERT_TRUE(sens.jacobian(act, x, Js));
    ASSERT_TRUE(cen.jacobian(act, x, Jc));
    const double worst = test_support::worst_column_relative_difference(Js, Jc);
    std::printf("[jacobian] curvature and section jumps, gravity, t = %.1f: %.2e\n", t, worst);
    // Central differences of the shear columns (EA L^2 / EI ~ 1e4) carry ~2e-6 round-off; a
    // missing jump term would be O(1) in the bending columns.
    EXPECT_LE(worst, 1e-5);
  }
}

TEST(ShootingVaryingBody, LoadedVaryingBodyConvergesAndBalancesGlobally) {
  rod::RodModel m = loaded_varying_rod();
  m.gravity_W_m_s2 = {0.0, 0.0, -9.81};
  m.material.density_profile =
      rod::Profile({0.0, 0.05, 0.05, m.length_m}, {1000, 1000, 2000, 1500});
  m.material.density_profile = rod::Profile(1000);
  ShootingSolver solver(m, rk4(64));
  Solution sol;
  const Summary s = solver.solve(rod::Loads::from_model(m), sol);
  ASSERT_TRUE(s.converged()) << s.message;
  // The base reaction balances the (varying) weight, the tip wrench and the strings.
  EXPECT_LE(s.force_imbalance_W_N.norm(), 1e-9);
  EXPECT_LE(s.moment_imbalance_W_Nm.norm(), 1e-10);
}

TEST(ShootingVaryingBody, ColdStartThroughTheCurvatureHomotopyFindsTheWarmStartsEquilibrium) {
  // bench/bench_varying_body's tapered tentacle (soft, hanging under its weight, w L^3 / EI of
  // several hundred) with a jump of the reference curvature at L/2. A cold solve first solves
  // the body without the jump, then with it (ShootingSolver::solve); without that homotopy it
  // took 525 IVPs. The same equilibrium must come out of the ordinary path: a warm start from
  // the uniform body's solution (no homotopy on warm starts), both at tolerance 1e-12.
  auto tentacle = [](bool tapered) {
    return rod::parse_scenario(test_support::hanging_tentacle(tapered));
  };
  const rod::RodModel m = tentacle(true), u = tentacle(false);
  const rod::Loads act = rod::Loads::from_model(m);
  ShootingSolver cold(m, rk4(40));
  Solution sc;
  const Summary s = cold.solve(act, sc);
  ASSERT_TRUE(s.converged()) << s.message;
  std::printf("[homotopy] cold solve: %d Newton iterations, %d IVPs\n", s.iterations, s.ivp_count);
  EXPECT_LE(s.ivp_count, 100);

  ShootingSolver uniform(u, rk4(40));
  Solution sw;
  ASSERT_TRUE(uniform.solve(rod::Loads::from_model(u), sw).converged());
  ShootingSolver warm(m, rk4(40));
  const Summary w = warm.solve(act, sw);
  ASSERT_TRUE(w.converged()) << w.message;
  const rod::Result rc = cold.make_result(act, sc, s), rw = warm.make_result(act, sw, w);
  const double d = (rc.tip_position_W_m - rw.tip_position_W_m).norm();
  std::printf("[homotopy] warm start from the uniform body: %d IVPs; tips differ by %.2e m\n",
              w.ivp_count, d);
  EXPECT_LE(d, 1e-10);
  EXPECT_LE((rc.tip_R_WB - rw.tip_R_WB).cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace tcasim::cosserat
