#pragma once
/// Rotations: the Lie group SO(3) and its algebra so(3).
/// Conventions: exp(hat(phi)) rotates by |phi| about phi/|phi|; the right Jacobian
/// satisfies exp(phi + dphi) = exp(phi) exp(Jr(phi) dphi) + O(dphi^2), the left one
/// exp(phi + dphi) = exp(Jl(phi) dphi) exp(phi). log returns the angle in [0, pi].
/// Small-angle branches: the coefficients of exp and the Jacobians are those of
/// common/lie_series.hpp (Taylor series in t^2 below kSeriesBelowAngleSquared); the
/// quaternion maps switch to their series below kSmallAngleThreshold; so every function is
/// accurate to round-off near 0. log goes through the quaternion (Shepperd's method, then
/// 2 atan2(|v|, w)), which keeps it accurate to round-off near pi.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/lie_series.hpp"

namespace tcasim::so3 {

/// Rotation angle [rad] below which exp_quaternion and log(quaternion) use their Taylor
/// series. At 1e-4 the first dropped term is O(theta^4) ~ 1e-16 relative (round-off).
inline constexpr double kSmallAngleThreshold = 1e-4;

// hat(v) w = v x w: common/lie_series.hpp.
/// Inverse of hat (reads the skew part of m).
Eigen::Vector3d vee(const Eigen::Matrix3d& m);

/// Rodrigues' formula.
Eigen::Matrix3d exp(const Eigen::Vector3d& phi);
/// Rotation vector of R, with angle in [0, pi] (R is expected to be a rotation).
Eigen::Vector3d log(const Eigen::Matrix3d& R);

/// Unit quaternion of the rotation vector phi.
Eigen::Quaterniond exp_quaternion(const Eigen::Vector3d& phi);
/// Rotation vector of a quaternion (its norm is irrelevant), angle in [0, pi]; q and
/// -q give the same result.
Eigen::Vector3d log(const Eigen::Quaterniond& q);

/// Right Jacobian Jr(phi).
Eigen::Matrix3d right_jacobian(const Eigen::Vector3d& phi);
/// Inverse of the right Jacobian (defined for |phi| < 2 pi).
Eigen::Matrix3d right_jacobian_inverse(const Eigen::Vector3d& phi);
/// Left Jacobian Jl(phi) = Jr(-phi).
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& phi);
/// Inverse of the left Jacobian (defined for |phi| < 2 pi).
Eigen::Matrix3d left_jacobian_inverse(const Eigen::Vector3d& phi);

}  // namespace tcasim::so3
