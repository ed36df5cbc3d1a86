// The node map of one beam element and its derivatives (beam_fe/internal/node_map.hpp).
#include "beam_fe/internal/node_map.hpp"

#include "common/so3.hpp"

namespace tcasim::beam_fe::internal {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void node_coordinates(const State& state, int first, int n, int ref,
                      const Eigen::Quaterniond& q_ref, const Matrix3d& R_ref, Vector3d* y,
                      Vector3d* psi) {
  for (int a = 0; a < n; ++a) {
    // Relative to the reference node (y' is unchanged since sum_a N_a' = 0): keeps the
    // moment rows free of |p| times the force round-off.
    y[a] = R_ref.transpose() * (state.p_W_m[first + a] - state.p_W_m[first + ref]);
    psi[a] = a == ref ? Vector3d::Zero() : so3::log(q_ref.conjugate() * state.q_WB[first + a]);
  }
}

void inverse_right_jacobian(const Vector3d& psi, double d, double dd_dt2, Matrix3d& A,
                            std::array<Matrix3d, 3>& dA) {
  // dd/dpsi_k = 2 d'(t2) psi_k.
  const Matrix3d K = so3::hat(psi);
  const Matrix3d K2 = K * K;
  A = Matrix3d::Identity() + 0.5 * K + d * K2;
  for (int k = 0; k < 3; ++k) {
    const Matrix3d Ek = so3::hat(Vector3d::Unit(k));
    dA[k] = 0.5 * Ek + 2.0 * dd_dt2 * psi[k] * K2 + d * (Ek * K + K * Ek);
  }
}

void node_map_jacobian(int n, int ref, const Matrix3d& R_ref, const Vector3d* y, const Matrix3d* A,
                       Eigen::Ref<Eigen::MatrixXd> B) {
  const int phr = 6 * ref + 3;  // column of the reference node's rotation increment
  const int dr = 6 * ref;       // column of the reference node's position increment
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    B.block<3, 3>(3 * a, 6 * a) = R_ref.transpose();
    B.block<3, 3>(3 * a, dr) = -R_ref.transpose();
    B.block<3, 3>(3 * a, phr) = so3::hat(y[a]);
    B.block<3, 3>(3 * n + 3 * a, 6 * a + 3) = A[a];
    B.block<3, 3>(3 * n + 3 * a, phr) = -A[a].transpose();
  }
}

void add_node_map_hessian(int n, int ref, const Matrix3d& R_ref, const Vector3d* y,
                          const Matrix3d* A, const std::array<Matrix3d, 3>* dA,
                          const Eigen::Ref<const Eigen::VectorXd>& grad_u,
                          Eigen::Ref<Eigen::MatrixXd> K) {
  const int phr = 6 * ref + 3;
  const int dr = 6 * ref;
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    const Vector3d gy = grad_u.segment<3>(3 * a);
    K.block<3, 3>(phr, phr) +=
        0.5 * (gy * y[a].transpose() + y[a] * gy.transpose()) - gy.dot(y[a]) * Matrix3d::Identity();
    const Matrix3d Hrd = so3::hat(gy) * R_ref.transpose();
    K.block<3, 3>(phr, 6 * a) += Hrd;
    K.block<3, 3>(phr, dr) -= Hrd;
    K.block<3, 3>(6 * a, phr) += Hrd.transpose();
    K.block<3, 3>(dr, phr) -= Hrd.transpose();
    // psi_a = log(exp(-theta_r) exp(psi_a) exp(theta_a)): dpsi = A dtheta_a - A^T dtheta_r
    // at 0, with A = Jr^-1(psi_a) and Jl^-1(psi) = Jr^-1(psi)^T.
    const Vector3d gp = grad_u.segment<3>(3 * n + 3 * a);
    auto DA = [&](const Vector3d& v) {
      return Matrix3d(v[0] * dA[a][0] + v[1] * dA[a][1] + v[2] * dA[a][2]);
    };
    Matrix3d Haa, Hrr, Har;
    for (int j = 0; j < 3; ++j) {
      const Vector3d ej = Vector3d::Unit(j);
      Haa.col(j) = DA(A[a] * ej).transpose() * gp - 0.5 * (A[a].transpose() * gp).cross(ej);
      Hrr.col(j) = DA(A[a].transpose() * ej) * gp + 0.5 * (A[a] * gp).cross(ej);
      Har.col(j) = -DA(A[a].transpose() * ej).transpose() * gp;
    }
    const int pha = 6 * a + 3;
    K.block<3, 3>(pha, pha) += Haa;
    K.block<3, 3>(phr, phr) += Hrr;
    K.block<3, 3>(pha, phr) += Har;
    K.block<3, 3>(phr, pha) += Har.transpose();
  }
}

}  // namespace tcasim::beam_fe::internal
