#include "common/so3.hpp"

#include <cmath>

namespace tcasim::so3 {

Eigen::Vector3d vee(const Eigen::Matrix3d& m) {
  // Skew part of m: (m - m^T)/2.
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

// [Sola2018] Rodrigues: exp(phi) = I + a hat(phi) + b hat(phi)^2.
Eigen::Matrix3d exp(const Eigen::Vector3d& phi) {
  const Coefficients<double> k = coefficients(phi.squaredNorm());
  const Eigen::Matrix3d K = hat(phi);
  return Eigen::Matrix3d::Identity() + k.a * K + k.b * K * K;
}

// [Sola2018] q = (cos(t/2), sin(t/2) phi/t).
Eigen::Quaterniond exp_quaternion(const Eigen::Vector3d& phi) {
  const double t = phi.norm();
  // sin(t/2)/t = 1/2 - t^2/48 + O(t^4).
  const double s = t < kSmallAngleThreshold ? 0.5 - t * t / 48.0 : std::sin(0.5 * t) / t;
  const Eigen::Vector3d v = s * phi;
  return Eigen::Quaterniond(std::cos(0.5 * t), v.x(), v.y(), v.z());
}

// [Sola2018] phi = 2 atan2(|v|, w) v/|v|, with w >= 0 so the angle is in [0, pi].
// atan2 is well conditioned at both ends, unlike acos of the trace near pi.
Eigen::Vector3d log(const Eigen::Quaterniond& q) {
  double w = q.w();
  Eigen::Vector3d v = q.vec();
  if (w < 0.0) {
    w = -w;
    v = -v;
  }
  const double n = v.norm();
  // Small branch (angle 2n/w < threshold): 2 atan2(n, w)/n = (2/w)(1 - n^2/(3 w^2) + O(n^4)).
  if (n < 0.5 * kSmallAngleThreshold * w) {
    const double r2 = (n * n) / (w * w);
    return (2.0 / w) * (1.0 - r2 / 3.0) * v;
  }
  return (2.0 * std::atan2(n, w) / n) * v;
}

Eigen::Vector3d log(const Eigen::Matrix3d& R) {
  // Eigen's matrix-to-quaternion conversion uses Shepperd's method (largest of
  // trace and diagonal as pivot), accurate for every angle including near pi.
  return log(Eigen::Quaterniond(R));
}

// [Sola2018] Jr(phi) = I - b hat(phi) + c hat(phi)^2.
Eigen::Matrix3d right_jacobian(const Eigen::Vector3d& phi) {
  const Coefficients<double> k = coefficients(phi.squaredNorm());
  const Eigen::Matrix3d K = hat(phi);
  return Eigen::Matrix3d::Identity() - k.b * K + k.c * K * K;
}

// [Sola2018] Jr^-1(phi) = I + hat(phi)/2 + d hat(phi)^2.
Eigen::Matrix3d right_jacobian_inverse(const Eigen::Vector3d& phi) {
  const Coefficients<double> k = coefficients(phi.squaredNorm());
  const Eigen::Matrix3d K = hat(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * K + k.d * K * K;
}

// [Sola2018] Jl(phi) = I + b hat(phi) + c hat(phi)^2 = Jr(-phi).
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& phi) { return right_jacobian(-phi); }

// [Sola2018] Jl^-1(phi) = I - hat(phi)/2 + d hat(phi)^2 = Jr^-1(-phi).
Eigen::Matrix3d left_jacobian_inverse(const Eigen::Vector3d& phi) {
  return right_jacobian_inverse(-phi);
}

}  // namespace tcasim::so3
