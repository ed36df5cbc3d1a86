// Inverse kinetostatics: tip Jacobian/compliance ([Pawlowski2019] Eqs. (41)-(42)), target
// solves (Eq. (40)) and the grasp temperature (Eqs. (43)-(44)).
#include "cosserat/inverse.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "support/input_error.hpp"

namespace tcasim::cosserat {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using units::degC_to_K;

/// Forward solves converge to a scaled residual of 1e-12 (tip error ~1e-14 m).
constexpr double kSolverTolerance = 1e-12;
/// J and C against central differences of full BVP solves: truncation O(h^2) with
/// h = 0.01 K / 1e-4 F_c, solve error 1e-14 m / h: both ~1e-8 of the entries.
constexpr double kAgainstBvpRelative = 1e-6;
/// The sensitivity and central FD-IVP variants differ by the differences' O(h^2) error.
constexpr double kCentralVsSensitivityRelative = 1e-6;
/// Forward differences are O(sqrt(eps)) accurate, amplified by B_u's conditioning.
constexpr double kForwardVsSensitivityRelative = 1e-5;
/// A reachable target is reached to this distance (the brief's requirement).
constexpr double kReached_m = 1e-9;

Options rk4(int steps = 48) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = kSolverTolerance;
  return o;
}

/// Circular EcoFlex rod (40 mm, 8 mm) standing under gravity with TCAs at radius 3 mm and
/// the given angles [deg] and temperatures [degC].
rod::RodModel tca_rod(const std::vector<double>& angles_deg, const std::vector<double>& t_degC) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  m.gravity_W_m_s2 = testing::kStandingGravity_m_s2;
  for (std::size_t k = 0; k < angles_deg.size(); ++k) {
    const double a = units::deg_to_rad(angles_deg[k]);
    testing::add_tca_string(m, "tca" + std::to_string(k), testing::manipulator_tca(),
                            0.003 * std::cos(a), 0.003 * std::sin(a), degC_to_K(t_degC[k]));
  }
  return m;
}

/// One gripper finger (Table I): 20 mm, 10 mm square, U-shaped TCA (count 2, coiled 20 mm)
/// at +3 mm body x, pointing down (body e3 = world -z), tip held along -x at its
/// undeformed position.
rod::RodModel gripper_finger() {
  rod::RodModel m = testing::square_rod(0.020, 0.010, 37.8e3, 0.5, 1040.0);
  m.R_WB0 << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  m.gravity_W_m_s2 = {0.0, 0.0, -units::kStandardGravity_m_s2};
  tca::Parameters p = testing::manipulator_tca()->parameters();
  p.coiled_length_m = 0.020;
  p.fiber_length_m = tca::fiber_length_from_pitch(0.020, units::deg_to_rad(15.0));
  auto t = std::make_shared<const tca::Tca>(p, testing::manipulator_tca()->material());
  testing::add_tca_string(m, "u-tca", t, 0.003, 0.0, degC_to_K(25.0), 2);
  m.tip_constraint = rod::TipConstraint{Vector3d(0.0, 0.0, -0.020), Vector3d(-1.0, 0.0, 0.0)};
  return m;
}

struct Pose {
  Vector3d p;
  Matrix3d R;
};

Pose solve_pose(ShootingSolver& solver, const rod::Loads& a, Solution sol) {
  const Summary s = solver.solve(a, sol);
  EXPECT_TRUE(s.converged()) << s.message;
  return {sol.tip_state.head<3>(), Eigen::Map<const Matrix3d>(sol.tip_state.data() + 3)};
}

Eigen::Matrix<double, 6, 1> pose_diff(const Pose& a, const Pose& b, const Matrix3d& R0) {
  const Matrix3d M = (a.R - b.R) * R0.transpose();
  Eigen::Matrix<double, 6, 1> d;
  d << a.p - b.p, 0.5 * Vector3d(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
  return d;
}

/// J and C by central differences of full (warm-started) BVP solves.
void bvp_differences(ShootingSolver& solver, const rod::RodModel& m, const rod::Loads& a,
                     const Solution& sol, const std::vector<int>& vars, MatrixXd& J, MatrixXd& C) {
  const Matrix3d R0 = Eigen::Map<const Matrix3d>(sol.tip_state.data() + 3);
  const double Fc = solver.characteristic_force_N();
  J.resize(6, vars.size());
  for (std::size_t k = 0; k < vars.size(); ++k) {
    const int i = vars[k];
    const bool tca = m.actuators[i].drive.type == rod::Drive::Type::kTca;
    const double v = tca ? a.actuators[i].segments[0].temperature_K : a.actuators[i].tension_N;
    const double h = tca ? 0.01 : 1e-3 * std::max(std::abs(v), Fc);
    rod::Loads ap = a, am = a;
    if (tca) {
      ap.set_temperature_K(i, v + h);
      am.set_temperature_K(i, v - h);
    } else {
      ap.actuators[i].tension_N = v + h;
      am.actuators[i].tension_N = v - h;
    }
    J.col(k) = pose_diff(solve_pose(solver, ap, sol), solve_pose(solver, am, sol), R0) / (2 * h);
  }
  C.resize(6, 6);
  for (int c = 0; c < 6; ++c) {
    const double h = 1e-4 * Fc * (c < 3 ? 1.0 : m.length_m);
    rod::Loads ap = a, am = a;
    if (c < 3) {
      ap.tip_force_W_N[c] += h;
      am.tip_force_W_N[c] -= h;
    } else {
      ap.tip_moment_W_Nm[c - 3] += h;
      am.tip_moment_W_Nm[c - 3] -= h;
    }
    C.col(c) = pose_diff(solve_pose(solver, ap, sol), solve_pose(solver, am, sol), R0) / (2 * h);
  }
}

void check_derivatives(const rod::RodModel& m, const std::vector<int>& vars) {
  ShootingSolver solver(m, rk4());
  rod::Loads a = rod::Loads::from_model(m);
  a.tip_force_W_N = {0.002, -0.001, 0.0};  // a loaded tip: C at a non-trivial point
  Solution sol;
  ASSERT_TRUE(solver.solve(a, sol).converged());
  MatrixXd Jb, Cb;
  bvp_differences(solver, m, a, sol, vars, Jb, Cb);
  TipDerivatives ds, dc, df;
  ASSERT_TRUE(tip_derivatives(solver, m, a, sol, vars, TipDerivativeMethod::kSensitivity, ds));
  ASSERT_TRUE(
      tip_derivatives(solver, m, a, sol, vars, TipDerivativeMethod::kCentralDifference, dc));
  ASSERT_TRUE(
      tip_derivatives(solver, m, a, sol, vars, TipDerivativeMethod::kForwardDifference, df));
  EXPECT_LE((ds.J - Jb).norm(), kAgainstBvpRelative * Jb.norm()) << ds.J << "\n\n" << Jb;
  EXPECT_LE((ds.C - Cb).norm(), kAgainstBvpRelative * Cb.norm()) << ds.C << "\n\n" << Cb;
  EXPECT_LE((dc.J - Jb).norm(), kAgainstBvpRelative * Jb.norm());
  EXPECT_LE((dc.C - Cb).norm(), kAgainstBvpRelative * Cb.norm());
  EXPECT_LE((dc.J - ds.J).norm(), kCentralVsSensitivityRelative * ds.J.norm());
  EXPECT_LE((dc.C - ds.C).norm(), kCentralVsSensitivityRelative * ds.C.norm());
  EXPECT_LE((df.J - ds.J).norm(), kForwardVsSensitivityRelative * ds.J.norm());
  EXPECT_LE((df.C - ds.C).norm(), kForwardVsSensitivityRelative * ds.C.norm());
  // The sensitivity variant needs one augmented IVP (plus two per tension drive); the
  // literal Eqs. (41)-(42) one IVP per unknown, actuation variable and wrench component.
  EXPECT_LT(ds.ivp_count, df.ivp_count);
  std::printf(
      "[J/C] |J| %.3e  rel. err. sens %.2e central %.2e forward %.2e | |C| %.3e  sens %.2e\n",
      Jb.norm(), (ds.J - Jb).norm() / Jb.norm(), (dc.J - Jb).norm() / Jb.norm(),
      (df.J - Jb).norm() / Jb.norm(), Cb.norm(), (ds.C - Cb).norm() / Cb.norm());
}

TEST(TipDerivatives, JacobianAndComplianceOfTemperaturesMatchBvpDifferences) {
  check_derivatives(tca_rod({0.0, 90.0}, {80.0, 110.0}), {0, 1});
}

TEST(TipDerivatives, JacobianOfTensionDrivesMatchesBvpDifferences) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  testing::add_tension_string(m, "a", 0.0030, 0.0010, 0.004);
  testing::add_tension_string(m, "b", -0.0020, 0.0025, 0.0015, 2);
  testing::add_tca_string(m, "c", testing::manipulator_tca(), 0.0005, -0.0031, degC_to_K(90.0));
  check_derivatives(m, {0, 1, 2});
}

TEST(TipDerivatives, RejectsAModelWithATipConstraint) {
  rod::RodModel m = gripper_finger();
  ShootingSolver solver(m, rk4());
  const rod::Loads a = rod::Loads::from_model(m);
  Solution sol;
  ASSERT_TRUE(solver.solve(a, sol).converged());
  TipDerivatives d;
  EXPECT_THROW(tip_derivatives(solver, m, a, sol, {0}, TipDerivativeMethod::kSensitivity, d),
               InputError);
}

/// Tip position of model m with its TCA temperatures set to t_degC.
Vector3d forward_tip(const rod::RodModel& m, const std::vector<double>& t_degC) {
  ShootingSolver solver(m, rk4());
  rod::Loads a = rod::Loads::from_model(m);
  for (std::size_t k = 0; k < t_degC.size(); ++k) a.set_temperature_K(k, degC_to_K(t_degC[k]));
  Solution sol;
  const Summary s = solver.solve(a, sol);
  EXPECT_TRUE(s.converged()) << s.message;
  return sol.tip_state.head<3>();
}

/// Solves for `target` from rest (every TCA at ambient).
InverseResult inverse_from_rest(const rod::RodModel& m, const Vector3d& target,
                                const InverseOptions& o) {
  ShootingSolver solver(m, rk4());
  rod::Loads a = rod::Loads::from_model(m);
  for (std::size_t k = 0; k < m.actuators.size(); ++k) a.set_temperature_K(k, degC_to_K(25.0));
  Solution sol;
  return solve_inverse(solver, m, target, o, a, sol);
}

TEST(Inverse, ReachesATargetGeneratedByAForwardSolve) {
  const rod::RodModel m = tca_rod({0.0, 90.0}, {25.0, 25.0});
  const Vector3d target = forward_tip(m, {70.0, 110.0});
  for (TipDerivativeMethod method :
       {TipDerivativeMethod::kSensitivity, TipDerivativeMethod::kForwardDifference}) {
    InverseOptions o;
    o.method = method;
    const InverseResult r = inverse_from_rest(m, target, o);
    EXPECT_TRUE(r.converged()) << r.message;
    EXPECT_LE(r.distance_m, kReached_m);
    EXPECT_LE((r.tip_position_W_m - target).norm(), kReached_m);
    // Two TCAs and a consistent 3D target: the generating temperatures (locally unique).
    EXPECT_NEAR(units::K_to_degC(r.values[0]), 70.0, 1e-3);
    EXPECT_NEAR(units::K_to_degC(r.values[1]), 110.0, 1e-3);
    std::printf("[inverse] %d iterations, %d forward solves, distance %.2e m\n", r.iterations,
                r.forward_solves, r.distance_m);
  }
}

TEST(Inverse, FarTargetIsReportedUnreachableWithItsResidualDistance) {
  const rod::RodModel m = tca_rod({0.0, 90.0}, {25.0, 25.0});
  const Vector3d target(0.05, 0.05, 0.0);
  const InverseResult r = inverse_from_rest(m, target, InverseOptions{});
  EXPECT_EQ(r.status, InverseResult::Status::kUnreachable) << r.message;
  EXPECT_FALSE(r.converged());
  EXPECT_GT(r.distance_m, 0.01);
  EXPECT_NEAR(r.distance_m, (r.tip_position_W_m - target).norm(), 1e-15);
  EXPECT_FALSE(r.message.empty());
}

TEST(Inverse, TargetBeyondTheMaximumTemperatureEndsAtTheBound) {
  const rod::RodModel m = tca_rod({0.0}, {25.0});
  const Vector3d target = forward_tip(m, {140.0});
  InverseOptions o;
  o.max_temperature_K = degC_to_K(100.0);
  const InverseResult r = inverse_from_rest(m, target, o);
  EXPECT_EQ(r.status, InverseResult::Status::kUnreachable) << r.message;
  EXPECT_NEAR(r.values[0], degC_to_K(100.0), 1e-12);
  EXPECT_TRUE(r.at_bound[0]);
  const Vector3d at_bound = forward_tip(m, {100.0});
  EXPECT_NEAR(r.distance_m, (at_bound - target).norm(), 1e-12);
}

TEST(Inverse, RedundantThreeTcasReachATwoDimensionalTarget) {
  const rod::RodModel m = tca_rod({0.0, 120.0, 240.0}, {25.0, 25.0, 25.0});
  const Vector3d target = forward_tip(m, {90.0, 60.0, 40.0});
  InverseOptions o;
  o.components = {true, true, false};  // tip x and y only
  const InverseResult r = inverse_from_rest(m, target, o);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LE(r.distance_m, kReached_m);
  EXPECT_LE((r.tip_position_W_m - target).head<2>().norm(), kReached_m);
}

TEST(Inverse, UnderActuatedReachesATargetOnItsCurveAndLeastSquaresOffIt) {
  const rod::RodModel m = tca_rod({0.0}, {25.0});
  const Vector3d on_curve = forward_tip(m, {120.0});
  const InverseResult r = inverse_from_rest(m, on_curve, InverseOptions{});
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LE(r.distance_m, kReached_m);
  EXPECT_NEAR(units::K_to_degC(r.values[0]), 120.0, 1e-4);
  // The tip moves in the x-z plane only: a target 2 mm off that plane is unreachable; the
  // least-squares optimum is the in-plane target, 2 mm away.
  const Vector3d off = on_curve + Vector3d(0.0, 0.002, 0.0);
  const InverseResult s = inverse_from_rest(m, off, InverseOptions{});
  EXPECT_EQ(s.status, InverseResult::Status::kUnreachable) << s.message;
  EXPECT_NEAR(s.distance_m, 0.002, 1e-9);
  EXPECT_NEAR(units::K_to_degC(s.values[0]), 120.0, 1e-3);
}

TEST(Inverse, PositionAndOrientationTargetIsReached) {
  const rod::RodModel m = tca_rod({0.0, 90.0}, {25.0, 25.0});
  ShootingSolver solver(m, rk4());
  rod::Loads g = rod::Loads::from_model(m);
  g.set_temperature_K(0, degC_to_K(95.0));
  g.set_temperature_K(1, degC_to_K(60.0));
  Solution gs;
  ASSERT_TRUE(solver.solve(g, gs).converged());
  InverseOptions o;
  o.target_R_WB = Matrix3d(Eigen::Map<const Matrix3d>(gs.tip_state.data() + 3));
  const InverseResult r = inverse_from_rest(m, gs.tip_state.head<3>(), o);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LE(r.distance_m, kReached_m);
  EXPECT_LE(r.orientation_error_rad * m.length_m, kReached_m);
  EXPECT_NEAR(units::K_to_degC(r.values[0]), 95.0, 1e-3);
}

TEST(Inverse, TensionDrivesReachATarget) {
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  testing::add_tension_string(m, "a", 0.003, 0.0, 0.0);
  testing::add_tension_string(m, "b", 0.0, 0.003, 0.0);
  rod::RodModel g = m;
  g.actuators[0].drive.tension_N = 0.004;
  g.actuators[1].drive.tension_N = 0.002;
  const Vector3d target = solve(g, rk4()).tip_position_W_m;
  ShootingSolver solver(m, rk4());
  rod::Loads a = rod::Loads::from_model(m);
  Solution sol;
  const InverseResult r = solve_inverse(solver, m, target, InverseOptions{}, a, sol);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LE(r.distance_m, kReached_m);
  EXPECT_NEAR(r.values[0], 0.004, 1e-9);
  EXPECT_NEAR(r.values[1], 0.002, 1e-9);
}

TEST(Grasp, Eq43TemperatureAgreesWithTheBlockedTipForwardSolve) {
  const rod::RodModel m = gripper_finger();
  GraspOptions o;
  o.mass_kg = 2e-3;
  o.friction = 1.1;
  o.fingers = 2;
  const GraspResult r = solve_grasp(m, rk4(), o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.required_force_N, 2e-3 * units::kStandardGravity_m_s2 / 2.2, 1e-15);
  ASSERT_TRUE(r.root_temperature_K.has_value());
  EXPECT_NEAR(r.temperature_K, *r.root_temperature_K, 1e-4);
  EXPECT_NEAR(r.blocked_normal_force_N, r.required_force_N, 1e-9 * r.required_force_N);
  std::printf("[grasp] 2 g: %.4f degC (Eq. 43, %d iterations), root %.4f degC\n",
              units::K_to_degC(r.temperature_K), r.iterations,
              units::K_to_degC(*r.root_temperature_K));
}

TEST(Grasp, TemperatureIncreasesWithMass) {
  const rod::RodModel m = gripper_finger();
  GraspOptions o;
  o.friction = 1.1;
  o.cross_check = false;
  double previous = 0.0;
  for (double mass_g : {1.0, 2.0, 3.0}) {
    o.mass_kg = mass_g * 1e-3;
    const GraspResult r = solve_grasp(m, rk4(), o);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_GT(r.temperature_K, previous);
    previous = r.temperature_K;
  }
}

TEST(Grasp, UnreachableForceIsReportedNotConverged) {
  const rod::RodModel m = gripper_finger();
  ShootingSolver cs(m, rk4());
  Solution sol;
  const double t_max = m.actuators[0].drive.tca->material().max_temperature_K;
  const double f_max = blocked_normal_force_N(cs, m, t_max, sol);
  ASSERT_TRUE(std::isfinite(f_max));
  GraspOptions o;
  o.friction = 1.1;
  o.mass_kg = 1.5 * f_max * o.friction * o.fingers / units::kStandardGravity_m_s2;
  const GraspResult r = solve_grasp(m, rk4(), o);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("at the maximum temperature"), std::string::npos) << r.message;
}

using test_support::expect_input_error;

TEST(InverseRejections, BadInputsNameTheFlagValueAndRule) {
  rod::RodModel free = gripper_finger();
  free.tip_constraint->normal_W.reset();
  GraspOptions o;
  o.mass_kg = 1e-3;
  o.friction = 1.1;
  expect_input_error([&] { solve_grasp(free, rk4(), o); }, "tip_constraint.normal");
  free.tip_constraint.reset();
  expect_input_error([&] { solve_grasp(free, rk4(), o); }, "tip_constraint.normal");
  o.mass_kg = -1.0;
  expect_input_error([&] { solve_grasp(gripper_finger(), rk4(), o); }, "mass");
  o.mass_kg = 1e-3;
  o.friction = 0.0;
  expect_input_error([&] { solve_grasp(gripper_finger(), rk4(), o); }, "friction");

  const rod::RodModel m = tca_rod({0.0, 90.0}, {25.0, 25.0});
  InverseOptions io;
  io.max_temperature_K = degC_to_K(20.0);  // below ambient
  expect_input_error([&] { inverse_from_rest(m, Vector3d(0, 0, 0.04), io); },
                     "max_temperature_degC");
}

TEST(InverseRejections, SegmentedTcaIsRefusedNotReducedToItsFirstSegment) {
  // Was silently solved with every segment at the first segment's temperature.
  const auto segment = [](rod::RodModel& m, int i) {
    rod::Drive& d = m.actuators[static_cast<std::size_t>(i)].drive;
    const double t_K = d.segments.front().temperature_K;
    d.segments = {tca::Segment{0.4, t_K}, tca::Segment{0.6, t_K + 20.0}};
    d.segmented = true;
  };
  rod::RodModel m = tca_rod({0.0, 90.0}, {25.0, 25.0});
  segment(m, 1);
  expect_input_error([&] { inverse_from_rest(m, Vector3d(0, 0, 0.04), InverseOptions{}); },
                     "actuators[1].drive.segments");
  // Held at its segments while only the uniform TCA is adjusted: allowed.
  InverseOptions only_first;
  only_first.actuators = {0};
  EXPECT_NO_THROW(inverse_from_rest(m, Vector3d(0, 0, 0.04), only_first));

  rod::RodModel finger = gripper_finger();
  segment(finger, 0);
  GraspOptions o;
  o.mass_kg = 1e-3;
  o.friction = 1.1;
  expect_input_error([&] { solve_grasp(finger, rk4(), o); }, "actuators[0].drive.segments");
}

}  // namespace
}  // namespace tcasim::cosserat
