#pragma once
/// The strings along the rod in the strain-derivative system of the shooting IVP
/// (docs/conventions.md "Body-frame ODEs solved by the shooting solver"): each loaded string i
/// at body offset r_i with unit tangent qh_i and c_i T_i adds
///   U_i A_i U_i^T, U_i = [I; hat(r_i)], A_i = c_i T_i (I - qh_i qh_i^T) / |q_i|
/// to M = diag(K_nu, K_omega). StringSystem assembles and solves M z = b (Woodbury for one string);
/// StrainSystem is its dense 6x6 fallback. Internal to the shooting solver.
#include <Eigen/Dense>
#include <cmath>
#include <optional>

#include "common/lie_series.hpp"

namespace tcasim::cosserat::internal {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

using so3::hat;

/// Solver of the symmetric 6x6 strain-derivative system M = [A B; B^T C] (fixed size, no
/// heap) by block elimination with Eigen's closed-form 3x3 inverses: S = C - B^T A^-1 B,
/// z_omega = S^-1 (b_omega - (A^-1 B)^T b_nu), z_nu = A^-1 b_nu - (A^-1 B) z_omega.
/// A = K_nu + sum A_i is positive definite unless strings are compressed beyond the
/// shear/axial stiffness; when A or S is numerically singular (relative determinant below
/// kSingularBlock) it falls back to LU with partial pivoting of M.
class StrainSystem {
 public:
  explicit StrainSystem(const Mat6& M) {
    const Mat3 A = M.topLeftCorner<3, 3>();
    const Mat3 B = M.topRightCorner<3, 3>();
    const Mat3 C = M.bottomRightCorner<3, 3>();
    block_ = well_conditioned(A);
    if (block_) {
      A_inv_ = A.inverse();
      AinvB_ = A_inv_ * B;
      const Mat3 S = C - B.transpose() * AinvB_;
      block_ = well_conditioned(S);
      if (block_) S_inv_ = S.inverse();
    }
    if (!block_) lu_.compute(M);
  }
  /// Solves M Z = R for a 6 x n right-hand side (in place).
  template <typename Rhs>
  void solve_in_place(Rhs& R) const {
    if (!block_) {
      R = lu_.solve(R);
      return;
    }
    const auto b_nu = R.template topRows<3>();
    const auto b_om = R.template bottomRows<3>();
    const Eigen::Matrix<double, 3, Rhs::ColsAtCompileTime, 0, 3, Rhs::MaxColsAtCompileTime> z_om =
        S_inv_ * (b_om - AinvB_.transpose() * b_nu);
    R.template topRows<3>() = A_inv_ * b_nu - AinvB_ * z_om;
    R.template bottomRows<3>() = z_om;
  }

 private:
  /// Relative determinant det(X) / prod(|X_ii|) below which a block counts as singular.
  static constexpr double kSingularBlock = 1e-10;
  static bool well_conditioned(const Mat3& X) {
    const double scale = std::abs(X(0, 0) * X(1, 1) * X(2, 2));
    const double det = X.determinant();
    return std::isfinite(det) && scale > 0.0 && std::abs(det) > kSingularBlock * scale;
  }
  bool block_ = false;
  Mat3 A_inv_, AinvB_, S_inv_;
  Eigen::PartialPivLU<Mat6> lu_;
};

/// The strain-derivative system M z = b with the structure of docs/conventions.md:
/// M = K + sum_i U_i A_i U_i^T, K = diag(K_nu, K_omega), U_i = [I; hat(r_i)] (6x3),
/// A_i = alpha_i (I - qh_i qh_i^T), alpha_i = c_i T_i / |q_i|. With one loaded string the
/// push-through (Woodbury) identity
///   M^-1 = K^-1 - K^-1 U (I + A G)^-1 A U^T K^-1,   G = U^T K^-1 U,
/// costs one 3x3 inverse and no 6x6 assembly; det M = det K det(I + A G), so I + A G is
/// singular exactly when M is. With several loaded strings, or when I + A G is numerically
/// singular, M is assembled and solved by StrainSystem.
class StringSystem {
 public:
  /// K_nu, K_omega and their reciprocals (precomputed by the caller).
  StringSystem(const Vec3& K_nu, const Vec3& K_omega, const Vec3& K_nu_inv, const Vec3& K_omega_inv)
      : kn_(K_nu), ko_(K_omega), kn_inv_(K_nu_inv), ko_inv_(K_omega_inv) {}
  /// Adds a loaded string at body offset r with A = alpha (I - qh qh^T).
  void add(const Vec3& r, double alpha, const Vec3& qh) {
    if (n_ == 0) {
      r_ = r;
      alpha_ = alpha;
      qh_ = qh;
    } else {
      if (n_ == 1) assemble(r_, alpha_, qh_);
      assemble(r, alpha, qh);
    }
    ++n_;
  }
  /// Factorizes after the last add.
  void factor() {
    if (n_ == 1) {
      // G = K_nu^-1 + hat(r)^T K_omega^-1 hat(r), written out (symmetric).
      const double x = r_.x(), y = r_.y(), z = r_.z();
      const Vec3& d = ko_inv_;
      Mat3 G;
      G << kn_inv_.x() + d.y() * z * z + d.z() * y * y, -d.z() * x * y, -d.y() * x * z,  //
          -d.z() * x * y, kn_inv_.y() + d.x() * z * z + d.z() * x * x, -d.x() * y * z,   //
          -d.y() * x * z, -d.x() * y * z, kn_inv_.z() + d.x() * y * y + d.y() * x * x;
      // W = I + A G with A G = alpha (G - qh (qh^T G)).
      const Eigen::RowVector3d qG = qh_.transpose() * G;
      Mat3 W = alpha_ * (G - qh_ * qG);
      W.diagonal().array() += 1.0;
      double det = 0.0;
      bool invertible = false;
      W.computeInverseAndDetWithCheck(W_inv_, det, invertible, 0.0);
      const double scale = std::abs(W(0, 0) * W(1, 1) * W(2, 2));
      if (invertible && std::isfinite(det) && scale > 0.0 && std::abs(det) > kSingular * scale) {
        woodbury_ = true;
        return;
      }
      assemble(r_, alpha_, qh_);
    }
    if (n_ >= 1) dense_.emplace(M_);
  }
  /// Solves M Z = R for a 6 x n right-hand side (in place).
  template <typename Rhs>
  void solve_in_place(Rhs& R) const {
    if (n_ >= 1 && !woodbury_) {
      dense_->solve_in_place(R);
      return;
    }
    for (int j = 0; j < R.cols(); ++j) {
      const Vec3 u_nu = kn_inv_.cwiseProduct(R.col(j).template head<3>());
      const Vec3 u_om = ko_inv_.cwiseProduct(R.col(j).template tail<3>());
      if (n_ == 0) {
        R.col(j).template head<3>() = u_nu;
        R.col(j).template tail<3>() = u_om;
        continue;
      }
      // w = (I + A G)^-1 A U^T u with U^T u = u_nu + hat(r)^T u_om = u_nu + u_om x r.
      const Vec3 t = u_nu + u_om.cross(r_);
      const Vec3 w = W_inv_ * (alpha_ * (t - qh_ * qh_.dot(t)));
      R.col(j).template head<3>() = u_nu - kn_inv_.cwiseProduct(w);
      R.col(j).template tail<3>() = u_om - ko_inv_.cwiseProduct(r_.cross(w));
    }
  }

 private:
  /// Relative determinant of I + A G below which the dense path is used.
  static constexpr double kSingular = 1e-10;
  void assemble(const Vec3& r, double alpha, const Vec3& qh) {
    if (!assembled_) {
      M_.setZero();
      M_.diagonal().head<3>() = kn_;
      M_.diagonal().tail<3>() = ko_;
      assembled_ = true;
    }
    const Mat3 A = alpha * (Mat3::Identity() - qh * qh.transpose());
    const Mat3 rh = hat(r);
    const Mat3 A_rh = A * rh;
    M_.topLeftCorner<3, 3>() += A;
    M_.topRightCorner<3, 3>() -= A_rh;
    M_.bottomLeftCorner<3, 3>() -= A_rh.transpose();        // hat(r) A = -(A hat(r))^T
    M_.bottomRightCorner<3, 3>() += rh.transpose() * A_rh;  // -hat(r) A hat(r)
  }
  Vec3 kn_, ko_, kn_inv_, ko_inv_;
  int n_ = 0;
  Vec3 r_, qh_;
  double alpha_ = 0.0;
  Mat3 W_inv_;
  bool woodbury_ = false;
  bool assembled_ = false;
  Mat6 M_;
  std::optional<StrainSystem> dense_;
};

}  // namespace tcasim::cosserat::internal
