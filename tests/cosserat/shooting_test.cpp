// Tests of the Cosserat shooting solver against closed forms, public benchmarks,
// physical signs, global equilibrium and convergence orders.
#include "cosserat/shooting.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "common/lie_series.hpp"
#include "common/root_finding.hpp"
#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "rod/closed_form.hpp"
#include "support/convergence.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::cosserat {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using testing::add_tension_string;
using units::kPi;

using so3::hat;

/// Tip pose of a constant-strain rod: g(L) = exp(L xi^) with xi = (nu, omega), computed
/// with Eigen's matrix exponential (independent of the solver and of so3).
Eigen::Matrix4d constant_strain_tip(const Vector3d& nu, const Vector3d& omega, double L) {
  Eigen::Matrix4d xi = Eigen::Matrix4d::Zero();
  xi.topLeftCorner<3, 3>() = hat(omega);
  xi.topRightCorner<3, 1>() = nu;
  return (L * xi).exp();
}

bool result_is_finite(const rod::Result& r) {
  bool ok = r.residual.has_value() && std::isfinite(*r.residual) && std::isfinite(r.wall_time_s) &&
            r.tip_position_W_m.allFinite() && r.tip_R_WB.allFinite();
  for (const auto& a : r.actuators)
    ok = ok && std::isfinite(a.tension_N) && std::isfinite(a.elongation_m);
  for (const auto& p : r.centerline_p_W_m) ok = ok && p.allFinite();
  for (const auto& R : r.centerline_R_WB) ok = ok && R.allFinite();
  if (r.bending_radius_m) ok = ok && std::isfinite(*r.bending_radius_m);
  return ok;
}

Options rk4_options(int steps, double tolerance = 1e-12) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = tolerance;
  return o;
}

Options rk6_options(int steps, double tolerance = 1e-12) {
  Options o = rk4_options(steps, tolerance);
  o.integrator.method = ode::Method::kRk6;
  return o;
}

Options rk8_options(int steps, double tolerance = 1e-12) {
  Options o = rk4_options(steps, tolerance);
  o.integrator.method = ode::Method::kRk8;
  return o;
}

// --------------------------------------------------------------------------------------
// Closed form: straight strings, constant offsets, uniform tensions, no gravity.

/// Solver tolerance for the closed-form tests: the scaled residual bounds the strain
/// error by ~tolerance relative, below the 1e-10 gate.
constexpr double kClosedFormSolverTolerance = 1e-12;
/// Gate of the closed-form comparisons (relative), as specified.
constexpr double kClosedFormRelativeError = 1e-10;
/// RK4 steps for the closed forms: the tip pose error of RK4 on R' = R hat(omega) is
/// ~ L (omega L) (omega h)^4 / 120 = 1e-13 L for omega L ~ 1.5 and 400 steps.
constexpr int kClosedFormSteps = 400;

struct ClosedForm {
  Vector3d nu, omega;
  std::vector<double> delta;
};

ClosedForm closed_form(const rod::RodModel& m, const std::vector<double>& tensions) {
  // docs/conventions.md "Closed form".
  std::vector<double> cT;
  for (std::size_t i = 0; i < m.actuators.size(); ++i)
    cT.push_back(m.actuators[i].count * tensions[i]);
  const rod::ConstantStrains s = rod::closed_form_strains(m, cT);
  return {Vector3d::UnitZ() + s.e, s.omega, rod::closed_form_elongations_m(m, cT)};
}

rod::RodModel soft_rod_with_strings() {
  // The circular manipulator's body without gravity, three strings at arbitrary offsets.
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  add_tension_string(m, "a", 0.0030, 0.0010, 0.004);
  add_tension_string(m, "b", -0.0020, 0.0025, 0.0015, 2);
  add_tension_string(m, "c", 0.0005, -0.0031, 0.0060);
  return m;
}

void expect_matches_closed_form(const rod::RodModel& m, const Solution& sol, const Summary& s,
                                const std::vector<double>& tensions, const rod::Result& res) {
  ASSERT_TRUE(s.converged()) << s.message;
  const ClosedForm cf = closed_form(m, tensions);
  const double L = m.length_m;
  // The unknowns hold nu(0) - nu* (shooting.hpp layout).
  const Vector3d nu0 = Vector3d::UnitZ() + sol.unknowns.head<3>(), om0 = sol.unknowns.segment<3>(3);
  EXPECT_LE((nu0 - cf.nu).norm(), kClosedFormRelativeError * cf.nu.norm());
  EXPECT_LE((om0 - cf.omega).norm(), kClosedFormRelativeError * cf.omega.norm());
  const Eigen::Matrix4d g = constant_strain_tip(cf.nu, cf.omega, L);
  const double tip_err = (res.tip_position_W_m - g.topRightCorner<3, 1>()).norm();
  EXPECT_LE(tip_err, kClosedFormRelativeError * L) << "tip error " << tip_err;
  EXPECT_LE((res.tip_R_WB - g.topLeftCorner<3, 3>()).norm(), kClosedFormRelativeError);
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    EXPECT_LE(std::abs(res.actuators[i].elongation_m - cf.delta[i]),
              kClosedFormRelativeError * std::abs(cf.delta[i]))
        << "actuator " << i << " delta " << res.actuators[i].elongation_m << " vs " << cf.delta[i];
    EXPECT_NEAR(res.actuators[i].tension_N, tensions[i],
                kClosedFormRelativeError * std::abs(tensions[i]));
  }
  std::printf("[closed form] nu err %.2e, omega err %.2e (rel), tip err %.2e L\n",
              (nu0 - cf.nu).norm() / cf.nu.norm(), (om0 - cf.omega).norm() / cf.omega.norm(),
              tip_err / L);
}

TEST(ShootingClosedForm, StraightStringsAtArbitraryOffsetsGiveExactConstantStrains) {
  const rod::RodModel m = soft_rod_with_strings();
  ShootingSolver solver(m, rk4_options(kClosedFormSteps, kClosedFormSolverTolerance));
  const rod::Loads act = rod::Loads::from_model(m);
  // Start away from the closed form (the default straight guess already is it).
  Solution sol;
  sol.valid = true;
  sol.unknowns.resize(6);
  sol.unknowns << 0.01, -0.02, -0.02, 1.0, -2.0, 0.5;  // nu(0) - nu* = (0.01, -0.02, -0.02)
  const Summary s = solver.solve(act, sol);
  EXPECT_GE(s.iterations, 2);
  const rod::Result res = solver.make_result(act, sol, s);
  expect_matches_closed_form(m, sol, s, {0.004, 0.0015, 0.006}, res);
}

TEST(ShootingClosedForm, TcaDriveTensionSolvesTheScalarEquationOfTheClosedForm) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  add_tension_string(m, "pull", -0.002, 0.001, 0.003);
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), 0.003, 0.0005,
                          units::degC_to_K(110.0));
  ShootingSolver solver(m, rk4_options(kClosedFormSteps, kClosedFormSolverTolerance));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;

  // Independent scalar solve: T = F_tca(delta(T)) with the linear closed-form delta(T), by
  // Brent's method (not the solvers' Newton).
  const tca::Tca& tca = *m.actuators[1].drive.tca;
  const double t_K = units::degC_to_K(110.0);
  auto g = [&](double T) {
    const ClosedForm cf = closed_form(m, {0.003, T});
    return T - tca.tension(cf.delta[1], t_K).tension_N;
  };
  // g is increasing (dF/ddelta > 0, ddelta/dT < 0). Bracket: T = 0 (the TCA pushes, g > 0)
  // and the T at which the closed-form delta reaches 0.1 m (inside Eq. (5)'s range; g < 0).
  const double d0 = closed_form(m, {0.003, 0.0}).delta[1];
  const double slope = closed_form(m, {0.003, 1.0}).delta[1] - d0;
  const double lo = (0.1 - d0) / slope, hi = 0.0;
  ASSERT_LT(g(lo), 0.0);
  ASSERT_GT(g(hi), 0.0);
  const auto root = roots::brent(g, lo, hi, g(lo), g(hi), 5e-18);
  ASSERT_TRUE(root.has_value());
  const double T_ref = root->x;
  ASSERT_LT(T_ref, 0.0) << "a heated extension TCA pushes";
  const rod::Result res = solver.make_result(act, sol, s);
  expect_matches_closed_form(m, sol, s, {0.003, T_ref}, res);
}

// --------------------------------------------------------------------------------------
// Roll-up and helix under an end moment (docs/conventions.md "Benchmark references").

/// RK4 error bound for a rotation at rate kappa over L with N steps: the RK4 amplification
/// of y' = i kappa y errs by (kappa h)^5 / 120 per step, so the tip (lever <= L) errs by at
/// most L (kappa L) (kappa h)^4 / 120; the gate is twice that bound.
double rk4_rotation_bound(double kappa, double L, int steps) {
  const double h = L / steps;
  return 2.0 * L * (kappa * L) * std::pow(kappa * h, 4) / 120.0;
}

class RollUp : public ::testing::TestWithParam<double> {};

TEST_P(RollUp, EndMomentRollsTheRodIntoACircleOfRadiusEIOverM) {
  const double fraction = GetParam();  // M = fraction * 2 pi EI / L: 0.5 half, 1 full circle
  rod::RodModel m = testing::circular_rod(1.0, 0.05, 1e6, 0.3, 0.0);
  const double EI = m.bending_torsion_stiffness().y();
  const double L = m.length_m;
  const double kappa = fraction * 2.0 * kPi / L;
  m.tip_moment_W_Nm = Vector3d(0.0, kappa * EI, 0.0);
  const int steps = 200;
  ShootingSolver solver(m, rk4_options(steps));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  // p(L) = ((1 - cos kappa L)/kappa, 0, sin(kappa L)/kappa).
  const Vector3d expected((1.0 - std::cos(kappa * L)) / kappa, 0.0, std::sin(kappa * L) / kappa);
  const double err = (res.tip_position_W_m - expected).norm();
  std::printf("[roll-up %.2f] tip error %.3e m (bound %.3e)\n", fraction, err,
              rk4_rotation_bound(kappa, L, steps));
  EXPECT_LE(err, rk4_rotation_bound(kappa, L, steps));
  if (fraction == 0.5) {  // half circle: tip at 2 L / pi from the root
    EXPECT_NEAR(res.tip_position_W_m.norm(), 2.0 * L / kPi, rk4_rotation_bound(kappa, L, steps));
  }
  if (fraction == 1.0) {  // full circle: tip back at the root
    EXPECT_LE(res.tip_position_W_m.norm(), rk4_rotation_bound(kappa, L, steps));
  }
}

INSTANTIATE_TEST_SUITE_P(HalfAndFullCircle, RollUp, ::testing::Values(0.5, 1.0));

TEST(Helix, EndMomentWithEqualBendingAndTorsionStiffnessGivesConstantCurvature) {
  rod::RodModel m = testing::circular_rod(1.0, 0.05, 1e6, 0.0, 0.0);  // G = E/2, J = 2 I: GJ = EI
  const double EI = m.bending_torsion_stiffness().x();
  ASSERT_NEAR(m.bending_torsion_stiffness().z(), EI, 1e-15 * EI);
  const Vector3d M = EI * Vector3d(2.0, 1.0, 3.0);
  m.tip_moment_W_Nm = M;
  const int steps = 400;
  ShootingSolver solver(m, rk4_options(steps));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  const Vector3d omega = M / EI;
  const Eigen::Matrix4d g = constant_strain_tip(Vector3d::UnitZ(), omega, m.length_m);
  const double bound = rk4_rotation_bound(omega.norm(), m.length_m, steps);
  const double err = (res.tip_position_W_m - g.topRightCorner<3, 1>()).norm();
  std::printf("[helix] tip error %.3e m (bound %.3e), omega(0) error %.2e\n", err, bound,
              (sol.unknowns.segment<3>(3) - omega).norm());
  EXPECT_LE(err, bound);
  EXPECT_LE((sol.unknowns.segment<3>(3) - omega).norm(), 1e-9 * omega.norm());
  // Constant curvature: omega(L) equals omega(0).
  EXPECT_LE((sol.tip_state.segment<3>(15) - omega).norm(), bound);
}

// --------------------------------------------------------------------------------------
// Mattiasson's cantilever (docs/conventions.md "Benchmark references").

struct MattiassonCase {
  double k, w, u;
  double rotation;  // NaN when not tabulated
};

class Mattiasson : public ::testing::TestWithParam<MattiassonCase> {};

/// The table has 5 decimals (rounding <= 5e-6) and the model is extensible with
/// EA = GA = 1e7 EI/L^2 (differs from the inextensible elastica by ~k 1e-7 L):
/// compare to 1e-5 L, the table's resolution (1e-6 would test the rounding).
constexpr double kMattiassonTolerance = 1e-5;

TEST_P(Mattiasson, TipDeflectionMatchesTheElasticaTable) {
  const MattiassonCase c = GetParam();
  const double L = 1.0, EI = 1.0;
  rod::RodModel m = testing::custom_rod(L, 1e7, 1e7, EI, EI);
  m.tip_force_W_N = Vector3d(c.k * EI / (L * L), 0.0, 0.0);  // dead load perpendicular to the rod
  ShootingSolver solver(m, rk4_options(400));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  const double w = res.tip_position_W_m.x() / L, u = 1.0 - res.tip_position_W_m.z() / L;
  const Vector3d t = res.tip_R_WB.col(2);
  const double rot = std::atan2(t.x(), t.z());
  std::printf("[Mattiasson k=%g] w/L %.6f (%.5f)  u/L %.6f (%.5f)  rot %.6f\n", c.k, w, c.w, u, c.u,
              rot);
  EXPECT_NEAR(w, c.w, kMattiassonTolerance);
  EXPECT_NEAR(u, c.u, kMattiassonTolerance);
  if (std::isfinite(c.rotation)) {
    EXPECT_NEAR(rot, c.rotation, kMattiassonTolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(Table, Mattiasson,
                         ::testing::Values(MattiassonCase{1, 0.30172, 0.05643, 0.46135},
                                           MattiassonCase{2, 0.49346, 0.16064, std::nan("")},
                                           MattiassonCase{5, 0.71379, 0.38763, std::nan("")},
                                           MattiassonCase{10, 0.81061, 0.55500, 1.43029}));

// --------------------------------------------------------------------------------------
// Physical signs (docs/conventions.md).

TEST(ShootingSigns, PositiveTensionAtPlusXBendsTowardPlusX) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  add_tension_string(m, "pull", 0.003, 0.0, 0.005);
  ShootingSolver solver(m, rk4_options(50, 1e-10));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  EXPECT_GT(sol.unknowns[4], 0.0);  // omega_y > 0
  EXPECT_GT(solver.make_result(act, sol, s).tip_position_W_m.x(), 0.0);
}

TEST(ShootingSigns, HeatedExtensionTcaAtPlusXBendsAwayTowardMinusX) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), 0.003, 0.0,
                          units::degC_to_K(120.0));
  ShootingSolver solver(m, rk4_options(50, 1e-10));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  EXPECT_LT(res.actuators[0].tension_N, 0.0) << "the heated extension TCA pushes";
  EXPECT_LT(res.tip_position_W_m.x(), 0.0);
}

// --------------------------------------------------------------------------------------
// Convergence of the IVP discretization inside the shooting solve.

rod::RodModel general_3d_rod() {
  // Gravity (oblique), a tip force and moment, a helical string and a straight one.
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  m.set_reference_curvature(Vector3d(1.0, -2.0, 0.5));
  m.gravity_W_m_s2 = Vector3d(3.0, -2.0, -9.0);
  m.tip_force_W_N = Vector3d(0.002, 0.001, -0.001);
  m.tip_moment_W_Nm = Vector3d(0.0, 1e-5, 2e-5);
  add_tension_string(m, "straight", 0.002, -0.001, 0.003);
  rod::Actuator h;
  h.name = "helix";
  h.routing.type = rod::Routing::Type::kHelix;
  h.routing.radius_m = 0.003;
  h.routing.phase_rad = 0.3;
  h.routing.turns_per_m = 25.0;  // one turn over the 40 mm body
  h.drive.tension_N = 0.004;
  const double w = 2.0 * kPi * h.routing.turns_per_m * h.routing.radius_m;
  h.rest_length_m = m.length_m * std::sqrt(1.0 + w * w);
  m.actuators.push_back(h);
  return m;
}

/// Tip position of the model's own actuation solved with `o` (expects convergence).
Vector3d converged_tip(const rod::RodModel& m, const Options& o) {
  ShootingSolver solver(m, o);
  Solution sol;
  const Summary s = solver.solve(rod::Loads::from_model(m), sol);
  EXPECT_TRUE(s.converged()) << s.message;
  return Vector3d(sol.tip_state.head<3>());
}

/// Tip errors of general_3d_rod() (gravity, helical strings) solved with `method` at each
/// step count against RK4 at ref_steps, as a table on stdout, inside order +- tolerance.
void ExpectTipOrderWithGravity(ode::Method method, int ref_steps, std::initializer_list<int> steps,
                               double order, double tolerance) {
  const rod::RodModel m = general_3d_rod();
  const Vector3d ref = converged_tip(m, rk4_options(ref_steps, 1e-13));
  std::vector<double> h, e;
  for (int n : steps) {
    Options o = rk4_options(n, 1e-13);
    o.integrator.method = method;
    h.push_back(m.length_m / n);
    e.push_back((converged_tip(m, o) - ref).norm());
  }
  std::printf("%s", test_support::convergence_table(h, e).c_str());
  test_support::ExpectOrderInBracket(h, e, order, tolerance);
}

TEST(ShootingConvergence, Rk4TipErrorHasObservedOrderFourWithGravity) {
  // From 32 steps (h = 1.25 mm, curvature x h <~ 0.05): coarser levels are pre-asymptotic
  // (observed 4.29 and 4.17 between 8, 16 and 32 steps).
  /// Bracket around the theoretical order 4 as specified.
  constexpr double kOrderTolerance = 0.15;
  ExpectTipOrderWithGravity(ode::Method::kRk4, 2048, {32, 64, 128, 256}, 4.0, kOrderTolerance);
}

TEST(ShootingConvergence, Rk6TipErrorHasObservedOrderSixWithGravity) {
  // Errors from ~1e-9 m down to ~3e-13 m, above the reference's (~1e-15 m at 4096 steps)
  // and the solve's round-off.
  /// Bracket around the theoretical order 6 (observed 5.94 and 5.96).
  constexpr double kOrderTolerance = 0.15;
  ExpectTipOrderWithGravity(ode::Method::kRk6, 4096, {8, 16, 32}, 6.0, kOrderTolerance);
}

TEST(ShootingConvergence, Rk8TipErrorHasObservedOrderEightWithGravity) {
  // Errors from ~1e-9 m down to ~4e-13 m, above the reference's and the solve's round-off.
  /// Bracket around the theoretical order 8 (observed 8.03, 8.11 and 8.08).
  constexpr double kOrderTolerance = 0.25;
  ExpectTipOrderWithGravity(ode::Method::kRk8, 4096, {6, 8, 12, 16}, 8.0, kOrderTolerance);
}

/// The multi-level solve `multi` (coarse, middle levels and the Richardson start with the
/// scheme's order) and the same solve without levels agree: the levels change only the
/// start. The result names the scheme's order.
void ExpectMultiLevelMatchesSingleLevel(const Options& multi, double order) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const rod::Loads act = rod::Loads::from_model(m);
  Options single = multi;
  single.coarse_steps = 0;
  ShootingSolver a(m, multi), b(m, single);
  Solution sa, sb;
  ASSERT_TRUE(a.solve(act, sa).converged());
  ASSERT_TRUE(b.solve(act, sb).converged());
  /// Both stop at a scaled residual <= 1e-11; the tip moves by <= 0.08 m per unit residual.
  constexpr double kTipAgreement_m = 1e-11;
  EXPECT_LE((sa.tip_state.head<3>() - sb.tip_state.head<3>()).norm(), kTipAgreement_m);
  const rod::Result res = a.make_result(act, sa, a.solve(act, sa));
  ASSERT_EQ(res.discretization.size(), 2u);
  EXPECT_EQ(res.discretization[1].first, "order");
  EXPECT_EQ(res.discretization[1].second, order);
}

TEST(ShootingConvergence, Rk6MultiLevelSolveMatchesASingleLevelSolve) {
  // Coarse 2, middle 4 and fine 16 steps.
  Options multi = rk6_options(16, 1e-11);
  multi.coarse_steps = 2;
  ExpectMultiLevelMatchesSingleLevel(multi, 6.0);
}

TEST(ShootingConvergence, Rk8MultiLevelSolveMatchesASingleLevelSolve) {
  // Coarse 2, middle 4 and fine 8 steps.
  Options multi = rk8_options(8, 1e-11);
  multi.coarse_steps = 2;
  ExpectMultiLevelMatchesSingleLevel(multi, 8.0);
}

TEST(ShootingConvergence, CvodeTipErrorScalesWithItsTolerance) {
  const rod::RodModel m = general_3d_rod();
  const auto tip = [&m](const Options& o) { return converged_tip(m, o); };
  const Vector3d ref = tip(rk4_options(2048, 1e-13));
  std::vector<double> tol, e;
  for (double rtol : {1e-5, 1e-7, 1e-9}) {
    Options o = rk4_options(2, 1e-12);
    o.integrator.method = ode::Method::kCvode;
    o.integrator.relative_tolerance = rtol;
    o.integrator.absolute_tolerance = rtol * 1e-3;
    tol.push_back(rtol);
    e.push_back((tip(o) - ref).norm() / m.length_m);
  }
  std::printf("%s", test_support::convergence_table(tol, e).c_str());
  // Tolerance proportionality: error ~ C rtol, i.e. order 1 in rtol. Adams' variable
  // order makes the constant drift; the bracket [0.5, 1.5] still fails if the error
  // stagnates (order ~0) or the tolerance is ignored.
  constexpr double kToleranceOrderSlack = 0.5;
  test_support::ExpectOrderInBracket(tol, e, 1.0, kToleranceOrderSlack);
  for (std::size_t i = 0; i < e.size(); ++i) EXPECT_LE(e[i], 100.0 * tol[i]);
}

// --------------------------------------------------------------------------------------
// Jacobian and global equilibrium.

rod::RodModel jacobian_test_rod() {
  rod::RodModel m = general_3d_rod();
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), -0.003, 0.001,
                          units::degC_to_K(90.0));
  return m;
}

Eigen::VectorXd jacobian_test_point() {
  Eigen::VectorXd x(7);
  x << 0.01, -0.02, -0.01, 2.0, -5.0, 1.0,
      -0.002;  // nu - nu*: away from equilibrium, bent, TCA pushing
  return x;
}

Eigen::MatrixXd jacobian_by(JacobianMethod method, int steps = 40) {
  const rod::RodModel m = jacobian_test_rod();
  Options o = rk4_options(steps);
  o.jacobian = method;
  ShootingSolver solver(m, o);
  Eigen::MatrixXd J;
  EXPECT_TRUE(solver.jacobian(rod::Loads::from_model(m), jacobian_test_point(), J));
  return J;
}

TEST(ShootingJacobian, SensitivityJacobianMatchesCentralDifferencesOfTheResidual) {
  const Eigen::MatrixXd Js = jacobian_by(JacobianMethod::kSensitivity);
  const Eigen::MatrixXd Jc = jacobian_by(JacobianMethod::kCentralDifference);
  const double worst = test_support::worst_column_relative_difference(Js, Jc);
  std::printf("[jacobian] sensitivity vs central differences: %.2e (worst column, relative)\n",
              worst);
  /// Central differences with h = eps^(1/3) max(|x|, typical) err by ~1e-10 relative
  /// (truncation ~h^2 times the third derivative, round-off ~eps |r| / h).
  constexpr double kCentralDifferenceError = 1e-7;
  EXPECT_LE(worst, kCentralDifferenceError);
}

TEST(ShootingJacobian, SensitivityJacobianMatchesCentralDifferencesWithCvode) {
  const rod::RodModel m = jacobian_test_rod();
  Options o = rk4_options(2);
  o.integrator.method = ode::Method::kCvode;
  o.integrator.relative_tolerance = 1e-12;
  o.integrator.absolute_tolerance = 1e-15;
  ShootingSolver sens(m, o);
  o.jacobian = JacobianMethod::kCentralDifference;
  ShootingSolver cen(m, o);
  Eigen::MatrixXd Js, Jc;
  ASSERT_TRUE(sens.jacobian(rod::Loads::from_model(m), jacobian_test_point(), Js));
  ASSERT_TRUE(cen.jacobian(rod::Loads::from_model(m), jacobian_test_point(), Jc));
  const double rel = (Js - Jc).norm() / Jc.norm();
  std::printf("[jacobian] CVODE sensitivity vs central differences: %.2e relative\n", rel);
  /// CVODE's adaptive steps make the residual map smooth only to ~rtol / h_fd = 1e-12 / 6e-6.
  constexpr double kCvodeJacobianError = 1e-5;
  EXPECT_LE(rel, kCvodeJacobianError);
}

TEST(ShootingJacobian, ForwardDifferenceJacobianMatchesCentralDifferences) {
  const Eigen::MatrixXd Jf = jacobian_by(JacobianMethod::kForwardDifference);
  const Eigen::MatrixXd Jc = jacobian_by(JacobianMethod::kCentralDifference);
  const double rel = (Jf - Jc).norm() / Jc.norm();
  std::printf("[jacobian] forward vs central: %.2e relative\n", rel);
  /// Forward differences err by O(sqrt(eps)) relative: ~1e-8 times curvature factors.
  constexpr double kForwardDifferenceError = 1e-6;
  EXPECT_LE(rel, kForwardDifferenceError);
}

TEST(ShootingJacobian, AllJacobianMethodsConvergeToTheSameSolution) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const rod::Loads act = rod::Loads::from_model(m);
  std::vector<Eigen::VectorXd> xs;
  for (JacobianMethod method : {JacobianMethod::kSensitivity, JacobianMethod::kForwardDifference,
                                JacobianMethod::kCentralDifference}) {
    Options o = rk4_options(20, 1e-10);  // 1e-12 is below this model's round-off floor (~1e-12)
    o.jacobian = method;
    ShootingSolver solver(m, o);
    Solution sol;
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << s.message;
    std::printf("[method %d] iterations %d, IVPs %d\n", static_cast<int>(method), s.iterations,
                s.ivp_count);
    xs.push_back(sol.unknowns);
  }
  /// The tolerance 1e-10 on the scaled residual fixes x to ~1e-10 relative (times the
  /// condition of the shooting Jacobian).
  constexpr double kSameSolution = 1e-8;
  EXPECT_LE((xs[1] - xs[0]).norm(), kSameSolution * xs[0].norm());
  EXPECT_LE((xs[2] - xs[0]).norm(), kSameSolution * xs[0].norm());
}

TEST(ShootingEquilibrium, BaseReactionBalancesGravityTipWrenchAndHelicalStrings) {
  const rod::RodModel m = general_3d_rod();
  ShootingSolver solver(m, rk4_options(400));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const double Fc = solver.characteristic_force_N();
  const double fi = s.force_imbalance_W_N.norm() / Fc;
  const double mi = s.moment_imbalance_W_Nm.norm() / (Fc * m.length_m);
  std::printf("[equilibrium] force %.2e Fc, moment %.2e Fc L\n", fi, mi);
  /// RK4 with 400 steps on this problem (curvatures ~ 50 1/m, h = 0.1 mm) integrates the
  /// loads to ~1e-12 relative; the solver tolerance is 1e-12.
  constexpr double kEquilibriumTolerance = 1e-10;
  EXPECT_LE(fi, kEquilibriumTolerance);
  EXPECT_LE(mi, kEquilibriumTolerance);
}

// --------------------------------------------------------------------------------------
// Initial guess of cold solves (docs/conventions.md "Initial guess").

/// A horizontal steel cantilever sagging under its weight (tip deflection 2.4 % of L): the
/// guess's base curvature carries the weight's base moment on the bent arc and matches the
/// converged one to the small-deflection error (~(deflection / L)^2; measured 1.5e-4),
/// where the guess without gravity (a straight rod) is off by the whole curvature. The base
/// shear w L does not depend on the shape: exact.
TEST(ShootingGuess, GravityGuessMatchesASaggingCantileverToItsSmallDeflection) {
  rod::RodModel m = testing::circular_rod(0.5, 0.002, 200e9, 0.25, 8000.0);
  m.gravity_W_m_s2 = {9.81, 0.0, 0.0};
  ShootingSolver solver(m, rk4_options(40));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  ASSERT_TRUE(solver.solve(act, sol).converged());
  const Eigen::VectorXd guess = solver.initial_guess(act);
  const double w = m.mass_per_length_kg_m(0.0) * 9.81;
  const double kappa0 = w * m.length_m * m.length_m / (2.0 * m.bending_torsion_stiffness().y());
  EXPECT_NEAR(std::abs(sol.unknowns[4]), kappa0, 1e-3 * kappa0);  // the beam formula itself
  constexpr double kSmallDeflection = 2e-3;  // relative, ~(0.024)^2 = 6e-4 with margin
  EXPECT_NEAR(guess[4], sol.unknowns[4], kSmallDeflection * kappa0);
  constexpr double kExactShear = 1e-8;  // relative: the solve tolerance, scaled
  EXPECT_NEAR(guess[0], sol.unknowns[0], kExactShear * std::abs(sol.unknowns[0]));
}

/// The paper's circular manipulator at 90 degC bends about twice as far as the TCA alone
/// would bend it: gravity pulls the bent body over. The guess with gravity lands within a
/// quarter of the error of the one without (measured: 3.6 against 17.8 1/m).
TEST(ShootingGuess, GravityGuessOfTheBentManipulatorIsCloserThanTheGuessWithout) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  rod::RodModel weightless = m;
  weightless.gravity_W_m_s2.setZero();
  ShootingSolver solver(m, rk4_options(64)), without(weightless, rk4_options(64));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  ASSERT_TRUE(solver.solve(act, sol).converged());
  const double with_error = std::abs(solver.initial_guess(act)[4] - sol.unknowns[4]);
  const double without_error =
      std::abs(without.initial_guess(rod::Loads::from_model(weightless))[4] - sol.unknowns[4]);
  EXPECT_LT(with_error, 0.25 * without_error) << with_error << " vs " << without_error;
}

// --------------------------------------------------------------------------------------
// Rejections and non-convergence: a status, never a NaN.

TEST(ShootingRejections, OneIterationWithoutContinuationReportsNotConverged) {
  const rod::RodModel m = general_3d_rod();
  Options o = rk4_options(40);
  o.max_iterations = 1;
  o.continuation = false;
  ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  EXPECT_FALSE(s.converged());
  EXPECT_EQ(s.status, Summary::Status::kMaxIterations);
  EXPECT_FALSE(s.message.empty());
  const rod::Result res = solver.make_result(act, sol, s);
  EXPECT_FALSE(res.converged);
  EXPECT_FALSE(res.message.empty());
  EXPECT_TRUE(result_is_finite(res));
}

TEST(ShootingRejections, AbsurdCompressiveTensionFailsWithAReasonAndNoNaN) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  // -1e6 N pushing on a rod of EA = 1.9 N: the axial strain would be ~5e5.
  add_tension_string(m, "absurd", 0.003, 0.0, -1e6);
  Options o = rk4_options(40);
  o.max_iterations = 10;
  ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  std::printf("[absurd] status %s: %s\n", to_string(s.status), s.message.c_str());
  const rod::Result res = solver.make_result(act, sol, s);
  EXPECT_TRUE(result_is_finite(res));
  EXPECT_TRUE(std::isfinite(s.residual));
  if (!s.converged()) {
    EXPECT_FALSE(res.message.empty());
  }
  EXPECT_FALSE(s.converged()) << "a tension of 5e5 EA should not give a converged rod";
}

// --------------------------------------------------------------------------------------
// The paper's manipulators: warm-started temperature sweeps 25..150 degC.

void sweep_manipulator(const rod::RodModel& m) {
  ShootingSolver solver(m, rk4_options(40, 1e-10));
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  double previous_radius = HUGE_VAL;
  bool previous_active = false;
  int active_points = 0;
  for (int t_degC = 25; t_degC <= 150; t_degC += 5) {
    act.set_temperature_K(0, units::degC_to_K(t_degC));
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << t_degC << " degC: " << s.message;
    const rod::Result res = solver.make_result(act, sol, s);
    ASSERT_TRUE(result_is_finite(res));
    // Active: the TCA pushes (heated extension TCA, negative tension).
    const bool active = res.actuators[0].tension_N < 0.0;
    const double radius = res.bending_radius_m.value_or(HUGE_VAL);
    std::printf("[%s] %3d degC: T %+.4e N, delta %.4e m, radius %.5g m, iters %d, ivps %d\n",
                m.name.c_str(), t_degC, res.actuators[0].tension_N, res.actuators[0].elongation_m,
                radius, s.iterations, s.ivp_count);
    if (active && previous_active) {
      EXPECT_LT(radius, previous_radius) << t_degC << " degC";
    }
    active_points += active;
    previous_active = active;
    previous_radius = radius;
  }
  EXPECT_GE(active_points, 10) << "the TCA should push over most of the sweep";
}

TEST(PaperManipulators, CircularManipulatorConvergesFrom25To150DegCAndRadiusDecreases) {
  sweep_manipulator(testing::circular_manipulator(units::degC_to_K(25.0)));
}

TEST(PaperManipulators, SquareManipulatorConvergesFrom25To150DegCAndRadiusDecreases) {
  sweep_manipulator(testing::square_manipulator(units::degC_to_K(25.0)));
}

// --------------------------------------------------------------------------------------
// Warm starts along a path (Solution::path).

TEST(ShootingPath, SweepWithPathExtrapolationMatchesColdSolvesWithFewerIvps) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(25.0));
  const Options o = rk6_options(10, 1e-10);
  ShootingSolver solver(m, o), cold_solver(m, o);
  rod::Loads act = rod::Loads::from_model(m);
  Solution with_path, without_path;
  int ivps_with = 0, ivps_without = 0;
  for (int t_degC = 25; t_degC <= 150; t_degC += 5) {
    act.set_temperature_K(0, units::degC_to_K(t_degC));
    const Summary a = solver.solve(act, with_path);
    without_path.path.clear();  // a warm start from the last solution only
    const Summary b = solver.solve(act, without_path);
    Solution cold;
    const Summary c = cold_solver.solve(act, cold);
    ASSERT_TRUE(a.converged() && b.converged() && c.converged()) << t_degC << " degC";
    if (t_degC > 25) {
      ivps_with += a.ivp_count;
      ivps_without += b.ivp_count;
    }
    EXPECT_LE(static_cast<int>(with_path.path.size()), ShootingSolver::kPathHistory);
    /// All three stop at a scaled residual <= 1e-10 (tip within ~1e-11 m of each other).
    constexpr double kTipAgreement_m = 2e-11;
    EXPECT_LE((with_path.tip_state.head<3>() - cold.tip_state.head<3>()).norm(), kTipAgreement_m)
        << t_degC << " degC";
  }
  std::printf("[path] 25 warm steps: %d IVPs with the path, %d from the last solution only\n",
              ivps_with, ivps_without);
  EXPECT_EQ(static_cast<int>(with_path.path.size()), ShootingSolver::kPathHistory);
  EXPECT_LT(ivps_with, ivps_without);
}

TEST(ShootingPath, ColdSolveResetsThePathAndAFailedSolveClearsIt) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(25.0));
  Options o = rk6_options(10, 1e-10);
  ShootingSolver solver(m, o);
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  for (int t_degC : {30, 35, 40}) {
    act.set_temperature_K(0, units::degC_to_K(t_degC));
    ASSERT_TRUE(solver.solve(act, sol).converged());
  }
  EXPECT_EQ(sol.path.size(), 3u);
  ASSERT_TRUE(solver.solve(act, sol).converged());  // the same actuation again
  EXPECT_EQ(sol.path.size(), 3u);
  sol.valid = false;  // a cold solve
  ASSERT_TRUE(solver.solve(act, sol).converged());
  EXPECT_EQ(sol.path.size(), 1u);
  o.max_iterations = 1;
  o.continuation = false;
  ShootingSolver weak(m, o);
  act.set_temperature_K(0, units::degC_to_K(150.0));
  ASSERT_FALSE(weak.solve(act, sol).converged());
  EXPECT_TRUE(sol.path.empty());
}

}  // namespace
}  // namespace tcasim::cosserat

namespace tcasim::cosserat {
namespace {

// --------------------------------------------------------------------------------------
// Segmented TCA drives (segments in series share the tension).

double manipulator_tension(const std::vector<tca::Segment>& segments) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(25.0));
  ShootingSolver solver(m, rk4_options(32, 1e-10));
  rod::Loads act = rod::Loads::from_model(m);
  act.actuators[0].segments = segments;
  Solution sol;
  const Summary s = solver.solve(act, sol);
  EXPECT_TRUE(s.converged()) << s.message;
  return sol.tensions_N[0];
}

TEST(ShootingSegments, EqualSegmentTemperaturesReproduceTheUniformTca) {
  const double T = units::degC_to_K(100.0);
  const double uniform = manipulator_tension({{1.0, T}});
  const double split = manipulator_tension({{0.3, T}, {0.7, T}});
  /// Both solves converge to 1e-10 Fc; series_tension's root finding adds its own tolerance.
  constexpr double kSameTension = 1e-8;
  EXPECT_NEAR(split, uniform, kSameTension * std::abs(uniform));
}

TEST(ShootingSegments, MixedSegmentTemperaturesGiveATensionBetweenTheUniformOnes) {
  const double cold = manipulator_tension({{1.0, units::degC_to_K(60.0)}});
  const double hot = manipulator_tension({{1.0, units::degC_to_K(120.0)}});
  const double mixed =
      manipulator_tension({{0.5, units::degC_to_K(60.0)}, {0.5, units::degC_to_K(120.0)}});
  std::printf("[segments] 60 degC %.5e N, 120 degC %.5e N, half/half %.5e N\n", cold, hot, mixed);
  EXPECT_LT(mixed, cold);
  EXPECT_GT(mixed, hot);
}

TEST(ShootingSummary, ADefaultSummarySaysItWasNeverRun) {
  const Summary none;
  EXPECT_EQ(none.status, Summary::Status::kNotRun);
  EXPECT_STREQ(to_string(none.status), "not_run");
  EXPECT_FALSE(none.equilibrium_residual.has_value());
}

TEST(ShootingSummary, CommonResidualIsTheScaledOneForTheModelsLoadsAndRescaledForOthers) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  ShootingSolver solver(m, rk4_options(40));
  rod::Loads loads = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(loads, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  EXPECT_EQ(s.characteristic_force_N, solver.characteristic_force_N());
  EXPECT_EQ(s.characteristic_force_N, rod::characteristic_force_N(m, loads));
  ASSERT_TRUE(s.equilibrium_residual.has_value());
  // Without a tip constraint and with the model's own loads the rows and F_c are the solver's.
  EXPECT_EQ(*s.equilibrium_residual, s.residual);
  const rod::Result res = solver.make_result(loads, sol, s);
  EXPECT_EQ(res.status, "converged");
  EXPECT_EQ(res.residual, s.equilibrium_residual);
  EXPECT_EQ(res.characteristic_force_N, s.characteristic_force_N);
  // Other loads: F_c of those loads; the solver keeps its own scaling.
  loads.tip_force_W_N = {0.0, 0.0, 3.0 * solver.characteristic_force_N()};  // pulls along the rod
  const Summary t = solver.solve(loads, sol);
  ASSERT_TRUE(t.converged()) << t.message;
  EXPECT_EQ(t.characteristic_force_N, rod::characteristic_force_N(m, loads));
  ASSERT_TRUE(t.equilibrium_residual.has_value());
  EXPECT_NEAR(*t.equilibrium_residual,
              t.residual * solver.characteristic_force_N() / t.characteristic_force_N,
              1e-15 * t.residual);
}

TEST(ShootingSummary, AFailedSolveReportsTheResidualOfItsReturnedPoint) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(150.0));
  Options o = rk4_options(40);
  o.max_iterations = 2;
  o.tolerance = 1e-30;  // below round-off: the solve cannot converge
  o.continuation = false;
  o.coarse_steps = 0;
  ShootingSolver solver(m, o);
  const rod::Loads loads = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(loads, sol);
  ASSERT_FALSE(s.converged());
  ASSERT_TRUE(s.equilibrium_residual.has_value());
  EXPECT_GT(*s.equilibrium_residual, o.tolerance);
  const rod::Result res = solver.make_result(loads, sol, s);
  EXPECT_EQ(res.status, to_string(s.status));
  EXPECT_NE(res.status, "converged");
  EXPECT_EQ(res.residual, s.equilibrium_residual);
}

}  // namespace
}  // namespace tcasim::cosserat
