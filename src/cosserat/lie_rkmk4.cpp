#include "cosserat/internal/lie_rkmk4.hpp"

#include <cmath>

#include "common/error.hpp"
#include "common/lie_series.hpp"

namespace tcasim::cosserat {

namespace {

using so3::hat;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Lie bracket of se(3) in (rho, phi) coordinates, the matrix commutator of the 4x4 hats:
/// [(rho1, phi1), (rho2, phi2)] = (phi1 x rho2 - phi2 x rho1, phi1 x phi2).
inline Vec6 bracket(const Vec6& X, const Vec6& Y) {
  Vec6 Z;
  const Vec3 r1 = X.head<3>(), p1 = X.tail<3>(), r2 = Y.head<3>(), p2 = Y.tail<3>();
  Z.head<3>() = p1.cross(r2) - p2.cross(r1);
  Z.tail<3>() = p1.cross(p2);
  return Z;
}

}  // namespace

Se3Exp::Se3Exp(const Vec3& rho, const Vec3& phi) : rho_(rho), phi_(phi) {
  // a, b, c of x = |phi|^2 and their x-derivatives, from one dual direction seeded on x.
  ad::Dual<double, 1> x(phi.squaredNorm());
  x.d[0] = 1.0;
  const so3::Coefficients<ad::Dual<double, 1>> k = so3::coefficients(x);
  a_ = k.a.v;
  b_ = k.b.v;
  c_ = k.c.v;
  da_ = k.a.d[0];
  db_ = k.b.d[0];
  dc_ = k.c.d[0];
  K_ = hat(phi);
  K2_ = K_ * K_;
  E_ = Mat3::Identity() + a_ * K_ + b_ * K2_;
  phi_x_rho_ = phi.cross(rho);
  phi_x_phi_x_rho_ = phi.cross(phi_x_rho_);
  t_ = rho + b_ * phi_x_rho_ + c_ * phi_x_phi_x_rho_;
}

void Se3Exp::derivative(const Vec3& drho, const Vec3& dphi, Mat3& dE, Vec3& dt) const {
  const double dx = 2.0 * phi_.dot(dphi);
  const Mat3 dK = hat(dphi);
  dE = (da_ * dx) * K_ + a_ * dK + (db_ * dx) * K2_ + b_ * (dK * K_ + K_ * dK);
  const Vec3 d_phi_x_rho = dphi.cross(rho_) + phi_.cross(drho);
  dt = drho + (db_ * dx) * phi_x_rho_ + b_ * d_phi_x_rho + (dc_ * dx) * phi_x_phi_x_rho_ +
       c_ * (dphi.cross(phi_x_rho_) + phi_.cross(d_phi_x_rho));
}

LieGroupRk4::LieGroupRk4(int dim, int directions, int steps, KinematicLayout layout)
    : dim_(dim), m_(directions), steps_(steps), total_(dim * (1 + directions)), lay_(layout) {
  require(dim >= 18, "LieGroupRk4 dimension", dim, "must be >= 18 (pose and strains)");
  require(directions >= 0, "LieGroupRk4 directions", directions, "must be >= 0");
  require(steps >= 1, "options.integrator.steps", steps, "must be >= 1");
  Yn_.resize(total_);
  Ys_.resize(total_);
  F_.assign(4, Eigen::VectorXd(total_));
  K_.assign(4, Eigen::MatrixXd(6, 1 + m_));
  theta_.resize(6, 1 + m_);
}

Vec6 LieGroupRk4::twist(const Eigen::VectorXd& Y, int b) const {
  Vec6 xi;
  // Block 0 holds the deviation nu - nu_reference; its sensitivities are those of nu.
  xi.head<3>() = Y.segment<3>(b * dim_ + lay_.nu);
  if (b == 0) xi.head<3>() += lay_.nu_reference;
  xi.tail<3>() = Y.segment<3>(b * dim_ + lay_.omega);
  return xi;
}

void LieGroupRk4::apply_increment(const Eigen::VectorXd& Yn, const Eigen::MatrixXd& theta,
                                  Eigen::VectorXd& Ys) const {
  const Se3Exp ex(theta.col(0).head<3>(), theta.col(0).tail<3>());
  const Eigen::Map<const Mat3> Rn(Yn.data() + lay_.R);
  const Vec3 pn = Yn.segment<3>(lay_.p);
  // g_s = g_n exp(Theta): R_s = R_n E, p_s = p_n + R_n t.
  Eigen::Map<Mat3>(Ys.data() + lay_.R) = Rn * ex.rotation();
  Ys.segment<3>(lay_.p) = pn + Rn * ex.translation();
  Mat3 dE;
  Vec3 dt;
  for (int j = 1; j <= m_; ++j) {
    const int o = j * dim_;
    const Eigen::Map<const Mat3> dRn(Yn.data() + o + lay_.R);
    const Vec3 dpn = Yn.segment<3>(o + lay_.p);
    ex.derivative(theta.col(j).head<3>(), theta.col(j).tail<3>(), dE, dt);
    Eigen::Map<Mat3>(Ys.data() + o + lay_.R) = dRn * ex.rotation() + Rn * dE;
    Ys.segment<3>(o + lay_.p) = dpn + dRn * ex.translation() + Rn * dt;
  }
}

bool LieGroupRk4::integrate(const ode::RhsFunction& f, double s0, double s1, Eigen::VectorXd& Y,
                            const ode::Observer& observer) {
  require(Y.size() == total_, "LieGroupRk4 state size", static_cast<double>(Y.size()),
          "must be dimension x (1 + directions) = " + std::to_string(total_));
  require(s1 > s0, "LieGroupRk4 s1", s1, "must be > s0");
  const double h = (s1 - s0) / steps_;
  if (observer) observer(s0, Y);
  // Classical RK4 tableau: stage nodes c = (0, 1/2, 1/2, 1), a_{i,i-1} = c_i, b = (1, 2, 2, 1)/6.
  static constexpr double kNode[4] = {0.0, 0.5, 0.5, 1.0};
  for (int n = 0; n < steps_; ++n) {
    const double s = s0 + n * h;
    Yn_ = Y;
    for (int i = 0; i < 4; ++i) {
      const Eigen::VectorXd* stage = &Yn_;
      if (i > 0) {
        theta_ = (kNode[i] * h) * K_[i - 1];
        Ys_ = Yn_ + (kNode[i] * h) * F_[i - 1];  // linear part; the pose is overwritten below
        apply_increment(Yn_, theta_, Ys_);
        stage = &Ys_;
      }
      f(s + kNode[i] * h, *stage, F_[i]);
      // Stage slope in the algebra: K = dexp^-1_{-Theta}(xi) truncated after [Theta, [Theta, xi]].
      const Vec6 xi = twist(*stage, 0);
      if (i == 0) {
        K_[0].col(0) = xi;
        for (int j = 1; j <= m_; ++j) K_[0].col(j) = twist(*stage, j);
        continue;
      }
      const Vec6 th = theta_.col(0);
      const Vec6 B1 = bracket(th, xi);
      const Vec6 B2 = bracket(th, B1);
      K_[i].col(0) = xi + 0.5 * B1 + B2 / 12.0;
      for (int j = 1; j <= m_; ++j) {
        const Vec6 dth = theta_.col(j);
        const Vec6 dxi = twist(*stage, j);
        const Vec6 dB1 = bracket(dth, xi) + bracket(th, dxi);
        const Vec6 dB2 = bracket(dth, B1) + bracket(th, dB1);
        K_[i].col(j) = dxi + 0.5 * dB1 + dB2 / 12.0;
      }
    }
    theta_ = (h / 6.0) * (K_[0] + 2.0 * K_[1] + 2.0 * K_[2] + K_[3]);
    Y = Yn_ + (h / 6.0) * (F_[0] + 2.0 * F_[1] + 2.0 * F_[2] + F_[3]);
    apply_increment(Yn_, theta_, Y);
    if (!Y.allFinite()) return false;
    if (observer) observer(n + 1 == steps_ ? s1 : s + h, Y);
  }
  return true;
}

}  // namespace tcasim::cosserat
