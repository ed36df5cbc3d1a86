// Tests of the Lie-group (RKMK4) kinematics of the shooting solver: the SE(3) exponential and
// its derivative, exactness for constant strains at any step count, observed order 4 with
// gravity, sensitivities against central differences, and agreement with RK4.
#include "cosserat/internal/lie_rkmk4.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "common/error.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"
#include "rod/closed_form.hpp"
#include "support/convergence.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::cosserat {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using testing::add_tension_string;

Options lie_options(int steps, double tolerance = 1e-12) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = tolerance;
  o.kinematics = Kinematics::kLieGroup;
  return o;
}

Options rk4_options(int steps, double tolerance = 1e-12) {
  Options o = lie_options(steps, tolerance);
  o.kinematics = Kinematics::kFlat;
  return o;
}

// --------------------------------------------------------------------------------------
// Se3Exp.

/// Rotation angles covering 0, the series branch, both sides of its threshold, and large angles.
const std::vector<double> kAngles = {0.0, 1e-7, 1e-3, 0.05, 0.0999999, 0.1000001, 0.7, 2.0, 3.1};

/// Se3Exp against so3::exp and so3::left_jacobian (independent implementations): both are
/// closed forms or series accurate to a few ulps of their O(1) entries.
constexpr double kSe3RoundOff = 1e-14;

TEST(Se3Exp, MatchesSo3ExpAndLeftJacobianOnBothBranches) {
  const Vector3d axis = Vector3d(0.3, -0.8, 0.5).normalized();
  const Vector3d rho(0.4, 1.1, -0.7);
  for (double angle : kAngles) {
    const Vector3d phi = angle * axis;
    const Se3Exp ex(rho, phi);
    EXPECT_LE((ex.rotation() - so3::exp(phi)).norm(), kSe3RoundOff) << "angle " << angle;
    EXPECT_LE((ex.translation() - so3::left_jacobian(phi) * rho).norm(), kSe3RoundOff)
        << "angle " << angle;
  }
}

TEST(Se3Exp, MatchesTheFourByFourMatrixExponential) {
  const Vector3d rho(0.4, 1.1, -0.7), phi(0.9, -1.2, 0.4);
  Eigen::Matrix4d X = Eigen::Matrix4d::Zero();
  X.topLeftCorner<3, 3>() = so3::hat(phi);
  X.topRightCorner<3, 1>() = rho;
  const Eigen::Matrix4d g = X.exp();
  const Se3Exp ex(rho, phi);
  EXPECT_LE((ex.rotation() - g.topLeftCorner<3, 3>()).norm(), kSe3RoundOff);
  EXPECT_LE((ex.translation() - g.topRightCorner<3, 1>()).norm(), kSe3RoundOff);
}

/// Central differences with step 1e-5 on O(1) functions: truncation ~h^2 = 1e-10, round-off
/// ~eps/h = 1e-11.
constexpr double kFdStep = 1e-5;
constexpr double kFdDerivativeError = 1e-9;

TEST(Se3Exp, DerivativeMatchesCentralDifferencesOnBothBranches) {
  const Vector3d axis = Vector3d(-0.2, 0.6, 0.9).normalized();
  const Vector3d rho(0.4, 1.1, -0.7), drho(-0.3, 0.2, 0.8), dphi(0.7, -0.5, 0.25);
  for (double angle : kAngles) {
    const Vector3d phi = angle * axis;
    Matrix3d dE;
    Vector3d dt;
    Se3Exp(rho, phi).derivative(drho, dphi, dE, dt);
    const Se3Exp p(rho + kFdStep * drho, phi + kFdStep * dphi);
    const Se3Exp m(rho - kFdStep * drho, phi - kFdStep * dphi);
    const Matrix3d dE_fd = (p.rotation() - m.rotation()) / (2.0 * kFdStep);
    const Vector3d dt_fd = (p.translation() - m.translation()) / (2.0 * kFdStep);
    EXPECT_LE((dE - dE_fd).norm(), kFdDerivativeError) << "angle " << angle;
    EXPECT_LE((dt - dt_fd).norm(), kFdDerivativeError) << "angle " << angle;
  }
}

// --------------------------------------------------------------------------------------
// The shooting solver with Kinematics::kLieGroup.

/// Closed-form comparisons (relative): round-off of a few dozen steps and of the Newton
/// solve to 1e-12 (the closed form itself is exact).
constexpr double kExactRelativeError = 1e-11;

TEST(LieGroupShooting, ConstantStrainRodIsExactAtAnyStepCount) {
  // Straight strings at constant offsets, no gravity: constant strains (docs/conventions.md).
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  m.set_reference_curvature(Vector3d(4.0, -30.0, 0.0));  // closed form: omega_z = 0
  add_tension_string(m, "a", 0.0030, 0.0010, 0.004);
  add_tension_string(m, "b", -0.0020, 0.0025, 0.0015, 2);
  const rod::Loads act = rod::Loads::from_model(m);
  // docs/conventions.md "Closed form".
  std::vector<double> cT;
  for (const rod::Actuator& a : m.actuators) cT.push_back(a.count * a.drive.tension_N);
  const rod::ConstantStrains cf = rod::closed_form_strains(m, cT);
  const Vector3d nu = Vector3d::UnitZ() + cf.e;
  const Vector3d omega = cf.omega;
  Eigen::Matrix4d X = Eigen::Matrix4d::Zero();
  X.topLeftCorner<3, 3>() = so3::hat(omega);
  X.topRightCorner<3, 1>() = nu;
  const Eigen::Matrix4d g = (m.length_m * X).exp();
  ASSERT_GT(omega.norm() * m.length_m, 1.0) << "the test needs a large rotation";
  for (int steps : {2, 4, 16, 64}) {
    ShootingSolver solver(m, lie_options(steps));
    Solution sol;
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << s.message;
    const rod::Result res = solver.make_result(act, sol, s);
    const double tip_err = (res.tip_position_W_m - g.topRightCorner<3, 1>()).norm() / m.length_m;
    const double rot_err = (res.tip_R_WB - g.topLeftCorner<3, 3>()).norm();
    std::printf("[RKMK4 constant strain] steps %3d: tip err %.2e L, R err %.2e\n", steps, tip_err,
                rot_err);
    EXPECT_LE(tip_err, kExactRelativeError) << steps << " steps";
    EXPECT_LE(rot_err, kExactRelativeError) << steps << " steps";
    EXPECT_LE((sol.unknowns.segment<3>(3) - omega).norm(), kExactRelativeError * omega.norm());
  }
}

/// A rod with non-constant strains: oblique gravity, reference curvature with torsion, a tip
/// wrench, a straight string, a helical string and a TCA (the shooting tests' 3-D rod).
rod::RodModel varying_strain_rod(bool with_tca) {
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
  h.routing.turns_per_m = 25.0;
  h.drive.tension_N = 0.004;
  const double w = 2.0 * units::kPi * h.routing.turns_per_m * h.routing.radius_m;
  h.rest_length_m = m.length_m * std::sqrt(1.0 + w * w);
  m.actuators.push_back(h);
  if (with_tca) {
    testing::add_tca_string(m, "tca", testing::manipulator_tca(), -0.003, 0.001,
                            units::degC_to_K(90.0));
  }
  return m;
}

Vector3d solved_tip(const rod::RodModel& m, const Options& o) {
  ShootingSolver solver(m, o);
  Solution sol;
  const Summary s = solver.solve(rod::Loads::from_model(m), sol);
  EXPECT_TRUE(s.converged()) << s.message;
  return sol.tip_state.head<3>();
}

TEST(LieGroupShooting, TipErrorHasObservedOrderFourWithGravity) {
  const rod::RodModel m = varying_strain_rod(false);
  const Vector3d ref = solved_tip(m, lie_options(2048, 1e-13));
  std::vector<double> h, e;
  for (int n : {16, 32, 64, 128}) {
    h.push_back(m.length_m / n);
    e.push_back((solved_tip(m, lie_options(n, 1e-13)) - ref).norm());
  }
  std::printf("%s", test_support::convergence_table(h, e).c_str());
  /// Bracket around the theoretical order 4 as specified.
  constexpr double kOrderTolerance = 0.15;
  test_support::ExpectOrderInBracket(h, e, 4.0, kOrderTolerance);
}

TEST(LieGroupShooting, ConvergesToTheSameSolutionAsRk4) {
  const rod::RodModel m = varying_strain_rod(true);
  const Vector3d lie = solved_tip(m, lie_options(400));
  const Vector3d rk4 = solved_tip(m, rk4_options(400));
  /// Both discretizations err by ~C h^4 ~ 1e-13 m at 400 steps (order test above).
  constexpr double kSameTip_m = 1e-11;
  EXPECT_LE((lie - rk4).norm(), kSameTip_m);
}

TEST(LieGroupShooting, SensitivityJacobianMatchesCentralDifferences) {
  const rod::RodModel m = varying_strain_rod(true);
  Eigen::VectorXd x(7);
  x << 0.01, -0.02, -0.01, 2.0, -5.0, 1.0,
      -0.002;  // nu - nu*: away from equilibrium, bent, TCA pushing
  auto jacobian_by = [&](JacobianMethod method) {
    Options o = lie_options(8);  // few, large steps: the group update's derivative matters
    o.jacobian = method;
    ShootingSolver solver(m, o);
    Eigen::MatrixXd J;
    EXPECT_TRUE(solver.jacobian(rod::Loads::from_model(m), x, J));
    return J;
  };
  const Eigen::MatrixXd Js = jacobian_by(JacobianMethod::kSensitivity);
  const Eigen::MatrixXd Jc = jacobian_by(JacobianMethod::kCentralDifference);
  const double worst = test_support::worst_column_relative_difference(Js, Jc);
  std::printf("[RKMK4 jacobian] sensitivity vs central differences: %.2e (worst column)\n", worst);
  /// Central differences with h = eps^(1/3) max(|x|, typical) err by ~1e-10 relative; an
  /// inexact derivative of the group update would err by O(1) in the rotation columns.
  constexpr double kCentralDifferenceError = 1e-7;
  EXPECT_LE(worst, kCentralDifferenceError);
}

TEST(LieGroupShooting, RotationStaysOrthogonalAtFewSteps) {
  const rod::RodModel m = varying_strain_rod(true);
  ShootingSolver solver(m, lie_options(4, 1e-10));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  ASSERT_EQ(res.centerline_R_WB.size(), 5u);
  /// The group update multiplies rotations: orthogonality holds to round-off.
  constexpr double kOrthogonality = 1e-14;
  for (const Matrix3d& R : res.centerline_R_WB) {
    EXPECT_LE((R.transpose() * R - Matrix3d::Identity()).norm(), kOrthogonality);
  }
}

TEST(LieGroupShooting, CvodeWithLieGroupKinematicsIsRejected) {
  rod::RodModel m = varying_strain_rod(false);
  Options o = lie_options(8);
  o.integrator.method = ode::Method::kCvode;
  EXPECT_THROW(ShootingSolver(m, o), InputError);
}

// --------------------------------------------------------------------------------------
// Warm starts.

TEST(WarmStart, SweepStepsReachTheColdSolutionWithFewIvps) {
  rod::RodModel m = testing::circular_manipulator(units::degC_to_K(25.0));
  const Options o = rk4_options(32, 1e-10);
  ShootingSolver warm_solver(m, o), cold_solver(m, o);
  rod::Loads act = rod::Loads::from_model(m);
  Solution warm;
  ASSERT_TRUE(warm_solver.solve(act, warm).converged());
  int warm_ivps = 0, cold_ivps = 0, steps = 0;
  for (int t = 30; t <= 150; t += 5, ++steps) {
    act.set_temperature_K(0, units::degC_to_K(t));
    const Summary sw = warm_solver.solve(act, warm);
    ASSERT_TRUE(sw.converged()) << t << " degC: " << sw.message;
    Solution cold;
    const Summary sc = cold_solver.solve(act, cold);
    ASSERT_TRUE(sc.converged()) << t << " degC: " << sc.message;
    warm_ivps += sw.ivp_count;
    cold_ivps += sc.ivp_count;
    /// Both satisfy ||r_scaled|| <= 1e-10 of the same discrete problem: same solution to
    /// ~1e-10 relative times the conditioning.
    constexpr double kSameSolution = 1e-7;
    EXPECT_LE((warm.unknowns - cold.unknowns).norm(), kSameSolution * cold.unknowns.norm())
        << t << " degC";
  }
  std::printf("[warm start] IVPs per step: warm %.2f, cold %.2f\n",
              static_cast<double>(warm_ivps) / steps, static_cast<double>(cold_ivps) / steps);
  EXPECT_LT(warm_ivps, cold_ivps);
}

TEST(WarmStart, UnchangedActuationConvergesWithoutAnIvp) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  ShootingSolver solver(m, rk4_options(32, 1e-10));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  ASSERT_TRUE(solver.solve(act, sol).converged());
  const Summary again = solver.solve(act, sol);
  EXPECT_TRUE(again.converged());
  EXPECT_EQ(again.ivp_count, 0) << "the IVP memo should answer the first residual";
}

// The cost check of warm starts (warm_start_pays): a warm point farther from convergence
// than the cold guess runs the cold path, whose fine level starts at the extrapolation of
// the coarse and middle solutions; a near one still goes straight to the fine level.
TEST(WarmStart, AWarmPointFartherThanTheGuessTakesTheColdPath) {
  const rod::RodModel m = testing::steel_tendon_rod();
  Options o = rk4_options(100, 1e-10);
  ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution cold;
  ASSERT_TRUE(solver.solve(act, cold).converged());
  Solution warm = cold;
  warm.unknowns *= 1.0 + 1e-3;  // scaled coarse residual ~7e-4, the guess's ~6e-6
  warm.path.clear();
  // Newton on the fine level from the warm point needs 3 iterations; the cold path one per
  // level.
  o.max_iterations = 2;
  o.continuation = false;
  ShootingSolver strict(m, o);
  const Summary s = strict.solve(act, warm);
  ASSERT_TRUE(s.converged()) << s.message;
  EXPECT_LE((warm.unknowns - cold.unknowns).lpNorm<Eigen::Infinity>(),
            1e-12 * cold.unknowns.lpNorm<Eigen::Infinity>());
}

TEST(WarmStart, ANearWarmPointGoesStraightToTheFineLevel) {
  rod::RodModel m = testing::steel_tendon_rod();
  ShootingSolver solver(m, rk4_options(100, 1e-10));
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary cold = solver.solve(act, sol);
  ASSERT_TRUE(cold.converged());
  sol.path.clear();
  act.actuators[0].tension_N *= 1.0 + 1e-7;  // a step the previous Jacobian takes at once
  const Summary warm = solver.solve(act, sol);
  ASSERT_TRUE(warm.converged()) << warm.message;
  // One coarse IVP for the check, the fine residuals at the start and after one step.
  EXPECT_LE(warm.ivp_count, 3) << "cold: " << cold.ivp_count;
  EXPECT_LT(warm.ivp_count, cold.ivp_count);
}

// --------------------------------------------------------------------------------------
// Multi-level cold start and coarse-level Jacobians (Options::coarse_steps).

TEST(MultiLevel, LevelsChangeOnlyTheStartNotTheSolution) {
  for (Kinematics kin : {Kinematics::kFlat, Kinematics::kLieGroup}) {
    const rod::RodModel m = varying_strain_rod(true);
    Options with = rk4_options(32, 1e-11);
    with.kinematics = kin;
    Options without = with;
    without.coarse_steps = 0;  // single level, exact fine Jacobians
    const rod::Loads act = rod::Loads::from_model(m);
    ShootingSolver a(m, with), b(m, without);
    Solution sa, sb;
    const Summary ra = a.solve(act, sa), rb = b.solve(act, sb);
    ASSERT_TRUE(ra.converged()) << ra.message;
    ASSERT_TRUE(rb.converged()) << rb.message;
    std::printf("[levels] IVPs with levels %d, single level %d\n", ra.ivp_count, rb.ivp_count);
    /// Both satisfy ||r_scaled|| <= 1e-11 of the same discrete problem.
    constexpr double kSameSolution = 1e-8;
    EXPECT_LE((sa.unknowns - sb.unknowns).norm(), kSameSolution * sb.unknowns.norm());
    EXPECT_LE((sa.tip_state.head<3>() - sb.tip_state.head<3>()).norm(), kSameSolution * m.length_m);
  }
}

TEST(BenchmarkConfiguration, CircularManipulatorAt32Rk4StepsIsWithin1e8mOfTheReference) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const Vector3d ref = solved_tip(m, rk4_options(4096, 1e-10));
  const Vector3d rk4 = solved_tip(m, rk4_options(32, 1e-10));
  const Vector3d lie = solved_tip(m, lie_options(32, 1e-10));
  std::printf("[benchmark configuration] tip error vs RK4 4096: RK4 32 %.2e m, RKMK4 32 %.2e m\n",
              (rk4 - ref).norm(), (lie - ref).norm());
  /// The speed target's accuracy requirement (tip position).
  constexpr double kTipError_m = 1e-8;
  EXPECT_LE((rk4 - ref).norm(), kTipError_m);
  EXPECT_LE((lie - ref).norm(), kTipError_m);
}

}  // namespace
}  // namespace tcasim::cosserat
