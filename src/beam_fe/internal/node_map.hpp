#pragma once
/// The node map of one beam element (element.cpp's header comment): the nodes' coordinates
/// relative to the reference node r, u = (y_a = R_r^T (p_a - p_r), psi_a = log(R_r^T R_a)),
/// its Jacobian B = du/dtheta in the material increments theta = (dp_a, dtheta_a) at 0 and its
/// second derivatives contracted with a gradient dE/du. Shared by the element kernel
/// (element.cpp) and the Kelvin-Voigt damping forces (dynamics_damping.cpp).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "beam_fe/beam_fe.hpp"

namespace tcasim::beam_fe::internal {

/// y_a = R_r^T (p_a - p_r) and psi_a = log(q_r^* q_a) (psi_r = 0 exactly) of the n nodes of
/// the element whose first node is `first`, r = first + ref; R_ref is q_ref's matrix.
void node_coordinates(const State& state, int first, int n, int ref,
                      const Eigen::Quaterniond& q_ref, const Eigen::Matrix3d& R_ref,
                      Eigen::Vector3d* y, Eigen::Vector3d* psi);

/// A = Jr^-1(psi) = I + K/2 + d K^2 (K = hat(psi)) and its derivatives
///   dA/dpsi_k = hat(e_k)/2 + 2 d'(t2) psi_k K^2 + d (hat(e_k) K + K hat(e_k)),
/// from d and d' = dd/dt2 at t2 = |psi|^2 (common/lie_series.hpp).
void inverse_right_jacobian(const Eigen::Vector3d& psi, double d, double dd_dt2, Eigen::Matrix3d& A,
                            std::array<Eigen::Matrix3d, 3>& dA);

/// B = du/dtheta at theta = 0 (6n x 6n, rows u = (y_a, psi_a), columns (dp_a, dtheta_a)), with
/// y_a = exp(-theta_r) R_r^T (p_a + dp_a - p_r - dp_r) (y_r = 0 identically) and
/// psi_a = log(exp(-theta_r) exp(psi_a) exp(theta_a)); A[a] = Jr^-1(psi_a). Sets the non-zero
/// blocks of B, which must be zero on entry.
void node_map_jacobian(int n, int ref, const Eigen::Matrix3d& R_ref, const Eigen::Vector3d* y,
                       const Eigen::Matrix3d* A, Eigen::Ref<Eigen::MatrixXd> B);

/// Adds to the element tangent K (6n x 6n) the second derivatives of u(theta) at 0 contracted
/// with grad_u = dE/du: the rotation of y_a by theta_r and, with dA[a] = dJr^-1/dpsi (from
/// inverse_right_jacobian), dpsi = A dtheta_a - A^T dtheta_r at 0 (Jl^-1(psi) = Jr^-1(psi)^T).
void add_node_map_hessian(int n, int ref, const Eigen::Matrix3d& R_ref, const Eigen::Vector3d* y,
                          const Eigen::Matrix3d* A, const std::array<Eigen::Matrix3d, 3>* dA,
                          const Eigen::Ref<const Eigen::VectorXd>& grad_u,
                          Eigen::Ref<Eigen::MatrixXd> K);

}  // namespace tcasim::beam_fe::internal
