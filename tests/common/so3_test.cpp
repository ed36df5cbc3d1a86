// Tests of the SO(3) module: hat/vee, exp/log round trips, quaternion forms and the
// Jacobians (checked by central differences of exp), at random points, near 0 on both
// sides of kSmallAngleThreshold, and near pi.
#include "common/so3.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/units.hpp"

namespace tcasim::so3 {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
constexpr double kPi = units::kPi;

// Round-off level for O(1) quantities built from a few dozen flops.
constexpr double kRoundOffTol = 1e-14;
// exp/log round trip near pi: the quaternion route keeps the angle accurate to a few
// ulps of pi (acos of the trace would lose ~sqrt(eps) ~ 1e-8 there).
constexpr double kNearPiRoundTripTol = 1e-13;
// Central difference with h = 1e-5: truncation ~h^2/6 |d3 exp| ~ 2e-11, round-off
// ~eps/h ~ 2e-11; 1e-9 leaves a margin of ~50.
constexpr double kFdStep = 1e-5;
constexpr double kFdJacobianTol = 1e-9;

// Angles near 0 on both sides of the quaternion maps' Taylor threshold (1e-4) and of the
// coefficients' series threshold (0.1 rad), near pi, and generic.
std::vector<Vector3d> test_points() {
  std::vector<Vector3d> points;
  const Vector3d axis = Vector3d(0.3, -0.5, 0.8).normalized();
  for (double angle :
       {0.0, 1e-9, 1e-5, kSmallAngleThreshold * (1.0 - 1e-9), kSmallAngleThreshold * (1.0 + 1e-9),
        1e-3, 0.0999, 0.1001, 0.5, 2.0, kPi - 1e-4, kPi - 1e-8})
    points.push_back(angle * axis);
  // Coordinate axes near pi exercise every pivot of the matrix-to-quaternion step.
  for (int k = 0; k < 3; ++k) points.push_back((kPi - 1e-8) * Vector3d::Unit(k));
  std::mt19937 rng(20190101u);  // fixed seed: reproducible
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  std::uniform_real_distribution<double> angle(0.0, kPi - 1e-3);
  for (int i = 0; i < 20; ++i) {
    const Vector3d dir = Vector3d(coord(rng), coord(rng), coord(rng)).normalized();
    points.push_back(angle(rng) * dir);
  }
  return points;
}

TEST(So3, HatIsCrossProductAndVeeInvertsIt) {
  std::mt19937 rng(7u);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 10; ++i) {
    const Vector3d v(u(rng), u(rng), u(rng));
    const Vector3d w(u(rng), u(rng), u(rng));
    EXPECT_LE((hat(v) * w - v.cross(w)).norm(), kRoundOffTol);
    EXPECT_LE((hat(v) + hat(v).transpose()).norm(), 0.0) << "hat must be exactly skew";
    EXPECT_EQ(vee(hat(v)), v);
  }
}

TEST(So3, VeeReadsOnlyTheSkewPart) {
  const Vector3d v(0.1, -0.2, 0.3);
  Matrix3d symmetric;
  symmetric << 1, 2, 3, 2, 4, 5, 3, 5, 6;
  EXPECT_LE((vee(hat(v) + symmetric) - v).norm(), kRoundOffTol);
}

TEST(So3, ExpIsOrthonormalWithUnitDeterminant) {
  for (const Vector3d& phi : test_points()) {
    const Matrix3d R = exp(phi);
    EXPECT_LE((R.transpose() * R - Matrix3d::Identity()).norm(), kRoundOffTol) << phi.transpose();
    EXPECT_NEAR(R.determinant(), 1.0, kRoundOffTol) << phi.transpose();
  }
}

TEST(So3, ExpRotatesAboutTheAxisByTheAngle) {
  // Cross-check Rodrigues against Eigen's AngleAxis (independent implementation).
  for (const Vector3d& phi : test_points()) {
    const double angle = phi.norm();
    if (angle == 0.0) {
      EXPECT_EQ(exp(phi), Matrix3d::Identity());
      continue;
    }
    const Matrix3d expected = Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
    EXPECT_LE((exp(phi) - expected).norm(), kRoundOffTol) << phi.transpose();
  }
}

TEST(So3, LogInvertsExpAtRandomSmallAndNearPiAngles) {
  for (const Vector3d& phi : test_points()) {
    const double tol = phi.norm() > 3.0 ? kNearPiRoundTripTol : kRoundOffTol;
    EXPECT_LE((log(exp(phi)) - phi).norm(), tol) << "phi = " << phi.transpose();
  }
}

TEST(So3, LogIsRelativelyAccurateAtTinyAngles) {
  // At |phi| = 1e-9 an absolute check is trivially met; require relative accuracy.
  for (double angle : {1e-12, 1e-9, 1e-5, 1e-3}) {
    const Vector3d phi = angle * Vector3d(1.0, 2.0, -2.0) / 3.0;
    EXPECT_LE((log(exp(phi)) - phi).norm(), 4.0 * kRoundOffTol * angle) << angle;
    EXPECT_LE((log(exp_quaternion(phi)) - phi).norm(), 4.0 * kRoundOffTol * angle) << angle;
  }
}

TEST(So3, LogReturnsAngleInZeroPiAndExpOfLogIsIdentityOnRotations) {
  // Angles beyond pi map back into [0, pi] as the same rotation.
  const Vector3d axis = Vector3d(-0.2, 0.9, 0.4).normalized();
  for (double angle : {kPi, kPi + 1e-8, 4.0, 6.0, 2.0 * kPi - 1e-3}) {
    const Matrix3d R = exp(angle * axis);
    const Vector3d phi = log(R);
    EXPECT_LE(phi.norm(), kPi + kRoundOffTol) << angle;
    EXPECT_LE((exp(phi) - R).norm(), kNearPiRoundTripTol) << angle;
  }
  const Vector3d at_pi = log(exp(kPi * axis));
  EXPECT_NEAR(at_pi.norm(), kPi, kNearPiRoundTripTol);
  EXPECT_NEAR(std::abs(at_pi.normalized().dot(axis)), 1.0, kRoundOffTol);
}

TEST(So3, QuaternionExpMatchesMatrixExpAndLogIgnoresSign) {
  for (const Vector3d& phi : test_points()) {
    const Eigen::Quaterniond q = exp_quaternion(phi);
    EXPECT_NEAR(q.norm(), 1.0, kRoundOffTol);
    EXPECT_LE((q.toRotationMatrix() - exp(phi)).norm(), kRoundOffTol) << phi.transpose();
    const double tol = phi.norm() > 3.0 ? kNearPiRoundTripTol : kRoundOffTol;
    EXPECT_LE((log(q) - phi).norm(), tol) << phi.transpose();
    const Eigen::Quaterniond minus_q(-q.w(), -q.x(), -q.y(), -q.z());
    EXPECT_LE((log(minus_q) - phi).norm(), tol) << phi.transpose();
  }
}

// Central difference of the right (or left) increment of exp in direction e_k.
Vector3d fd_right_increment(const Vector3d& phi, int k) {
  const Vector3d dh = kFdStep * Vector3d::Unit(k);
  const Matrix3d Rt = exp(phi).transpose();
  return (log(Rt * exp(phi + dh)) - log(Rt * exp(phi - dh))) / (2.0 * kFdStep);
}
Vector3d fd_left_increment(const Vector3d& phi, int k) {
  const Vector3d dh = kFdStep * Vector3d::Unit(k);
  const Matrix3d Rt = exp(phi).transpose();
  return (log(exp(phi + dh) * Rt) - log(exp(phi - dh) * Rt)) / (2.0 * kFdStep);
}

TEST(So3, RightJacobianMatchesCentralDifferenceOfExp) {
  for (const Vector3d& phi : test_points()) {
    const Matrix3d Jr = right_jacobian(phi);
    for (int k = 0; k < 3; ++k)
      EXPECT_LE((fd_right_increment(phi, k) - Jr.col(k)).norm(), kFdJacobianTol)
          << "phi = " << phi.transpose() << ", column " << k;
  }
}

TEST(So3, LeftJacobianMatchesCentralDifferenceOfExp) {
  for (const Vector3d& phi : test_points()) {
    const Matrix3d Jl = left_jacobian(phi);
    for (int k = 0; k < 3; ++k)
      EXPECT_LE((fd_left_increment(phi, k) - Jl.col(k)).norm(), kFdJacobianTol)
          << "phi = " << phi.transpose() << ", column " << k;
  }
}

TEST(So3, JacobianInversesAreInverses) {
  for (const Vector3d& phi : test_points()) {
    EXPECT_LE((right_jacobian(phi) * right_jacobian_inverse(phi) - Matrix3d::Identity()).norm(),
              kRoundOffTol)
        << phi.transpose();
    EXPECT_LE((left_jacobian(phi) * left_jacobian_inverse(phi) - Matrix3d::Identity()).norm(),
              kRoundOffTol)
        << phi.transpose();
  }
}

TEST(So3, LeftJacobianIsRightJacobianOfNegatedVectorAndRotatedRightJacobian) {
  for (const Vector3d& phi : test_points()) {
    EXPECT_LE((left_jacobian(phi) - right_jacobian(-phi)).norm(), kRoundOffTol);
    // Jl(phi) = exp(phi) Jr(phi): an identity independent of how either is coded.
    EXPECT_LE((left_jacobian(phi) - exp(phi) * right_jacobian(phi)).norm(), kRoundOffTol)
        << phi.transpose();
  }
}

TEST(So3, JacobiansAreContinuousAcrossTheSmallAngleThresholds) {
  const Vector3d axis = Vector3d(1.0, -1.0, 0.5).normalized();
  // Both branches agree to round-off at each switch (no jump of the first dropped term):
  // the quaternion maps' at kSmallAngleThreshold, the coefficients' at
  // sqrt(kSeriesBelowAngleSquared). The two points lie a few ulps apart, so the functions'
  // own change between them (slope O(1)) stays far below the tolerance.
  for (const double threshold : {kSmallAngleThreshold, std::sqrt(kSeriesBelowAngleSquared)}) {
    const Vector3d below = threshold * (1.0 - 1e-15) * axis;
    const Vector3d above = threshold * (1.0 + 1e-15) * axis;
    EXPECT_LE((exp(below) - exp(above)).norm(), kRoundOffTol) << threshold;
    EXPECT_LE((right_jacobian(below) - right_jacobian(above)).norm(), kRoundOffTol) << threshold;
    EXPECT_LE((right_jacobian_inverse(below) - right_jacobian_inverse(above)).norm(), kRoundOffTol)
        << threshold;
    EXPECT_LE((exp_quaternion(below).coeffs() - exp_quaternion(above).coeffs()).norm(),
              kRoundOffTol)
        << threshold;
  }
}

TEST(So3, SmallAngleJacobiansMatchTheirSeries) {
  // Jr = I - K/2 + K^2/6 - K^3/24 + ..., Jr^-1 = I + K/2 + K^2/12 + O(K^4): the
  // dropped terms are bounded by t^3 (|K| = t), so the Taylor branch (below 0.1 rad) and
  // the closed form above it must both agree with the series to that level.
  for (double angle : {1e-9, 1e-5, 1e-3, 0.2}) {
    const Vector3d phi = angle * Vector3d(0.6, 0.0, -0.8);
    const Matrix3d K = hat(phi);
    const Matrix3d I = Matrix3d::Identity();
    const double dropped = angle * angle * angle + kRoundOffTol;
    EXPECT_LE((right_jacobian(phi) - (I - K / 2.0 + K * K / 6.0)).norm(), dropped) << angle;
    EXPECT_LE((right_jacobian_inverse(phi) - (I + K / 2.0 + K * K / 12.0)).norm(), dropped)
        << angle;
  }
}

}  // namespace
}  // namespace tcasim::so3
