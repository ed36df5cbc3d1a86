#pragma once
/// Lie-group integration of the Cosserat kinematics for the shooting solver
/// (Options::kinematics = Kinematics::kLieGroup).
///
/// The pose g = (R_WB, p_W) obeys g' = g xi^ with the body twist xi = (nu_B, omega_B)
/// ([Pawlowski2019] Eqs. (7)-(8)). The Runge-Kutta-Munthe-Kaas method of order 4 (H. Munthe-Kaas,
/// "High order Runge-Kutta methods on manifolds", Appl. Numer. Math. 29, 1999) writes
/// g(s_n + sigma) = g_n exp(Theta(sigma)) and integrates
///   Theta' = dexp^-1_{-Theta}(xi) = xi + [Theta, xi]/2 + [Theta, [Theta, xi]]/12 + O(Theta^4)
/// (truncated after two commutators, enough for order 4) with the classical RK4 tableau.
/// Every other state component (strains, c, delta) is stepped by classical RK4 with the same
/// stages, so the coupled scheme is order 4, and it is exact for a constant twist (then
/// every stage has Theta parallel to xi, the commutators vanish and g_{n+1} = g_n exp(h xi)).
/// R stays a rotation to round-off at any step count.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "common/ode.hpp"

namespace tcasim::cosserat {

/// SE(3) exponential of the twist (rho, phi) [rho: translation, phi: rotation vector]:
/// exp([hat(phi) rho; 0 0]) = [E t; 0 1] with E = Exp(phi) (Rodrigues) and t = Jl(phi) rho
/// (Jl: left Jacobian of SO(3)), plus exact directional derivatives. The scalar
/// coefficients are functions of x = |phi|^2 (smooth at phi = 0):
///   a = sin(t)/t, b = (1 - cos t)/t^2, c = (t - sin t)/t^3,  t = sqrt(x),
///   E = I + a hat(phi) + b hat(phi)^2,   Jl = I + b hat(phi) + c hat(phi)^2,
/// from common/lie_series.hpp (Taylor series in x below its kSeriesBelowAngleSquared), their
/// x-derivatives by one dual direction.
class Se3Exp {
 public:
  Se3Exp(const Eigen::Vector3d& rho, const Eigen::Vector3d& phi);
  /// Exp(phi).
  const Eigen::Matrix3d& rotation() const { return E_; }
  /// Jl(phi) rho.
  const Eigen::Vector3d& translation() const { return t_; }
  /// Directional derivatives dE, dt along (drho, dphi).
  void derivative(const Eigen::Vector3d& drho, const Eigen::Vector3d& dphi, Eigen::Matrix3d& dE,
                  Eigen::Vector3d& dt) const;

 private:
  Eigen::Vector3d rho_, phi_, phi_x_rho_, phi_x_phi_x_rho_;
  Eigen::Matrix3d K_, K2_, E_;
  Eigen::Vector3d t_;
  double a_, b_, c_, da_, db_, dc_;  // coefficients and their derivatives d/dx
};

/// Where the pose and the twist sit in the flattened state (shooting.hpp layout by default):
/// p_W at [p, p+3), R_WB column-major at [R, R+9), nu_B - nu_reference at [nu, nu+3) (the
/// shooting state holds the deviation from nu* = e3), omega_B at [omega, omega+3).
struct KinematicLayout {
  int p = 0;
  int R = 3;
  int nu = 12;
  int omega = 15;
  Eigen::Vector3d nu_reference = Eigen::Vector3d::UnitZ();
};

/// Fixed-step RKMK4 integrator of a flattened state y (dimension `dim`), optionally augmented
/// with forward sensitivities: Y = (y, Y_1, ..., Y_m), each block of length dim, Y_j = dy/dx_j.
/// The RHS f(s, Y, dY) is the one of the flattened state (and of its variational equations);
/// its p and R components are not used (the pose is advanced by the group update). With m > 0
/// the blocks Y_j are propagated by the exact derivative of the discrete map (the linear
/// stages by linearity, the group update by Se3Exp::derivative), so they are the exact
/// sensitivities of the discrete solution if f's direction blocks are the exact linearization.
/// No allocation after construction.
class LieGroupRk4 {
 public:
  /// dim: state dimension; directions: number m of sensitivity blocks; steps: equal steps (>= 1).
  LieGroupRk4(int dim, int directions, int steps, KinematicLayout layout = {});

  /// Integrates Y from s0 to s1 > s0 in place (size dim (1 + m)); the observer sees the full
  /// Y at every step node (s0 included). Returns false (Y left partial) if Y became non-finite.
  bool integrate(const ode::RhsFunction& f, double s0, double s1, Eigen::VectorXd& Y,
                 const ode::Observer& observer = {});

  int steps() const { return steps_; }

  int dimension() const { return dim_; }
  int directions() const { return m_; }

 private:
  /// Twist (nu, omega) of block b of Y as a 6-vector (rho = nu, phi = omega).
  Eigen::Matrix<double, 6, 1> twist(const Eigen::VectorXd& Y, int b) const;
  /// Ys = Yn moved by the group increment Theta (block 0) and dTheta (blocks 1..m).
  void apply_increment(const Eigen::VectorXd& Yn, const Eigen::MatrixXd& theta,
                       Eigen::VectorXd& Ys) const;

  int dim_, m_, steps_, total_;
  KinematicLayout lay_;
  Eigen::VectorXd Yn_, Ys_;
  std::vector<Eigen::VectorXd> F_;  // per stage: f at the stage (dim (1 + m))
  std::vector<Eigen::MatrixXd> K_;  // per stage, 6 x (1 + m): Lie-algebra slopes and derivatives
  Eigen::MatrixXd theta_;           // 6 x (1 + m)
};

}  // namespace tcasim::cosserat
