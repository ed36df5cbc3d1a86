// Kelvin-Voigt damping of the FE dynamics: the strain-rate history per quadrature point and the
// nodal forces of the viscous stress (beam_fe/internal/dynamics_damping.hpp).
//
// The forces of the work function W(eps) = sigma_h . eps + 1/2 eps . C eps follow the chain of
// the element kernel (element.cpp): increments theta -> u = (y_a, psi_a) -> g = (y', psi, psi')
// -> eps = (exp(psi)^T y' - e3, Jr(psi) psi'), r = B^T G^T dW/dg; the tangent is
// B^T G^T (d2W/dg2) G B (d2W/dg2 = F^T C F + sum_k sigma_k d2 eps_k / dg2, sigma = sigma_h + C
// eps), plus the second derivatives of u(theta) contracted with the gradient, plus hat(r_rot)/2
// per node. Here the derivatives of W(g) come from nested dual numbers over the 9 components of g
// (the element kernel writes them in closed form); the node map's are the kernel's formulas.
#include "beam_fe/internal/dynamics_damping.hpp"

#include <cmath>

#include "beam_fe/internal/node_map.hpp"
#include "beam_fe/internal/quadrature.hpp"
#include "common/dual.hpp"
#include "common/lie_series.hpp"
#include "common/so3.hpp"

namespace tcasim::beam_fe::damping {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;
using internal::gauss_rule;
using internal::shape;

/// W(g) = sigma_h . eps(g) + 1/2 eps(g) . C eps(g) as a nested dual over g: its gradient (F^T
/// sigma) and Hessian.
void work_jet(const Vector9d& g, const Vector6d& sigma_h, const Vector6d& C, Vector9d& grad,
              Matrix9d& hess) {
  using D1 = ad::Dual<double, 9>;
  using D2 = ad::Dual<D1, 9>;
  Eigen::Matrix<D2, 9, 1> x;
  for (int i = 0; i < 9; ++i) {
    x[i] = D2(g[i]);
    x[i].v.d[i] = 1.0;
    x[i].d[i] = D1(1.0);
  }
  const Eigen::Matrix<D2, 3, 1> yp = x.segment<3>(0), ps = x.segment<3>(3), pp = x.segment<3>(6);
  const D2 t2 = ps.dot(ps);
  const so3::Coefficients<D2> k = so3::coefficients(t2);
  const Eigen::Matrix<D2, 3, 3> K = so3::hat(ps);
  const Eigen::Matrix<D2, 3, 3> K2 = K * K;
  Eigen::Matrix<D2, 3, 3> I = Eigen::Matrix<D2, 3, 3>::Identity();
  // exp(psi)^T = I - a K + b K^2, Jr(psi) = I - b K + c K^2.
  Eigen::Matrix<D2, 3, 1> e = (I - k.a * K + k.b * K2) * yp;
  e[2] = e[2] - D2(1.0);
  const Eigen::Matrix<D2, 3, 1> om = (I - k.b * K + k.c * K2) * pp;
  D2 s(0.0);
  for (int i = 0; i < 3; ++i) {
    s = s + e[i] * (D2(sigma_h[i]) + D2(0.5 * C[i]) * e[i]) +
        om[i] * (D2(sigma_h[3 + i]) + D2(0.5 * C[3 + i]) * om[i]);
  }
  for (int i = 0; i < 9; ++i) {
    grad[i] = s.d[i].v;
    for (int j = 0; j < 9; ++j) hess(i, j) = s.d[i].d[j];
  }
}

}  // namespace

double viscosity_at(const rod::RodModel& model, double s_m,
                    const std::optional<double>& override_Pa_s) {
  if (override_Pa_s) return *override_Pa_s;
  return model.material.viscosity_profile.value(s_m);
}

void add_viscous_forces(const Discretization& disc, const State& state,
                        const std::vector<Vector6d>& sigma, const std::vector<Vector6d>& stiffness,
                        VectorXd& r, Eigen::SparseMatrix<double>* Kg) {
  const int order = disc.order(), n = order + 1, nu = 6 * n;
  const int ref = order == 1 ? 0 : 1;
  std::vector<double> xi, w;
  const std::size_t per_element = sigma.size() / static_cast<std::size_t>(disc.element_count());
  gauss_rule(static_cast<int>(per_element), xi, w);
  double N[3], dNxi[3];
  for (int e = 0; e < disc.element_count(); ++e) {
    const int first = e * order;
    const double he = disc.element_length_m(e);
    const Eigen::Quaterniond q_ref = state.q_WB[first + ref];
    const Matrix3d R_ref = q_ref.toRotationMatrix();
    std::vector<Vector3d> y(n), psi(n);
    std::vector<Matrix3d> A(n, Matrix3d::Identity());
    std::vector<std::array<Matrix3d, 3>> dA(n);
    internal::node_coordinates(state, first, n, ref, q_ref, R_ref, y.data(), psi.data());
    for (int a = 0; a < n; ++a) {
      if (a == ref) continue;
      // A = Jr^-1(psi) and dA/dpsi_k (internal/node_map.hpp), d' from a dual.
      ad::Dual<double, 1> t2(psi[a].squaredNorm());
      t2.d[0] = 1.0;
      const so3::Coefficients<ad::Dual<double, 1>> c = so3::coefficients(t2);
      internal::inverse_right_jacobian(psi[a], c.d.v, c.d.d[0], A[a], dA[a]);
    }
    VectorXd grad_u = VectorXd::Zero(nu);
    MatrixXd hess_u = MatrixXd::Zero(nu, nu);
    for (std::size_t gp = 0; gp < xi.size(); ++gp) {
      shape(order, xi[gp], N, dNxi);
      const double wj = w[gp] * 0.5 * he;
      double dN[3];
      for (int a = 0; a < n; ++a) dN[a] = dNxi[a] * 2.0 / he;
      Eigen::Matrix<double, 9, Eigen::Dynamic> G =
          Eigen::Matrix<double, 9, Eigen::Dynamic>::Zero(9, nu);
      for (int a = 0; a < n; ++a) {
        G.block<3, 3>(0, 3 * a) = dN[a] * Matrix3d::Identity();
        G.block<3, 3>(3, 3 * n + 3 * a) = N[a] * Matrix3d::Identity();
        G.block<3, 3>(6, 3 * n + 3 * a) = dN[a] * Matrix3d::Identity();
      }
      Vector9d g = Vector9d::Zero();
      for (int a = 0; a < n; ++a) {
        g.segment<3>(0) += dN[a] * y[a];
        g.segment<3>(3) += N[a] * psi[a];
        g.segment<3>(6) += dN[a] * psi[a];
      }
      Vector9d gg;
      Matrix9d S;
      const std::size_t point = static_cast<std::size_t>(e) * xi.size() + gp;
      work_jet(g, sigma[point], stiffness[point], gg, S);
      grad_u += wj * G.transpose() * gg;
      if (Kg) hess_u += wj * G.transpose() * S * G;
    }
    // B = du/dtheta (internal/node_map.hpp).
    MatrixXd B = MatrixXd::Zero(nu, nu);
    internal::node_map_jacobian(n, ref, R_ref, y.data(), A.data(), B);
    const VectorXd res = B.transpose() * grad_u;
    const int base = 6 * first - 6;
    for (int i = 0; i < nu; ++i)
      if (base + i >= 0) r[base + i] += res[i];
    if (!Kg) continue;
    MatrixXd K = B.transpose() * hess_u * B;
    internal::add_node_map_hessian(n, ref, R_ref, y.data(), A.data(), dA.data(), grad_u, K);
    for (int a = 0; a < n; ++a) {
      K.block<3, 3>(6 * a + 3, 6 * a + 3) += 0.5 * so3::hat(Vector3d(res.segment<3>(6 * a + 3)));
    }
    for (int i = 0; i < nu; ++i) {
      if (base + i < 0) continue;
      for (int j = 0; j < nu; ++j)
        if (base + j >= 0) Kg->coeffRef(base + i, base + j) += K(i, j);
    }
  }
}

StrainRateHistory::StrainRateHistory(const Discretization& disc, const rod::RodModel& model,
                                     const std::optional<double>& eta_override,
                                     const AlphaParameters& ap, double dt_s)
    : disc_(disc), ap_(ap), h_(dt_s), c_e_(ap.gamma / (ap.beta * dt_s)) {
  // docs/conventions.md "Dynamics": B_se = diag(eta_s A, eta_s A, eta A),
  // B_bt = diag(eta I_x, eta I_y, eta_s J), eta_s = eta / (2 (1 + poisson)), at each point's s.
  for (const PointStrain& p : disc.strains(disc.reference_state())) {
    const double eta = viscosity_at(model, p.s_m, eta_override);
    const rod::SectionStiffness Bs = rod::section_stiffness(model.section.properties_at(p.s_m), eta,
                                                            model.material.shear_modulus(eta));
    Vector6d B;
    B << Bs.shear_extension, Bs.bending_torsion;
    B_.push_back(B);
    cB_.push_back(c_e_ * B);
  }
}

std::vector<Vector6d> StrainRateHistory::strains(const State& state) const {
  std::vector<Vector6d> out;
  for (const PointStrain& p : disc_.strains(state)) {
    Vector6d e;
    e << p.nu_B - Vector3d::UnitZ(), p.omega_B;
    out.push_back(e);
  }
  return out;
}

Vector6d StrainRateHistory::history(std::size_t k) const {
  return (1.0 - ap_.gamma / ap_.beta) * eps_t_[k] +
         h_ * (1.0 - ap_.gamma / (2.0 * ap_.beta)) * a_eps_[k];
}

void StrainRateHistory::reset(const State& state) {
  eps_ = strains(state);
  eps_t_.assign(eps_.size(), Vector6d::Zero());
  a_eps_.assign(eps_.size(), Vector6d::Zero());
}

void StrainRateHistory::add_forces(const State& trial, VectorXd& r,
                                   Eigen::SparseMatrix<double>* K) const {
  std::vector<Vector6d> sigma_h(eps_.size());
  for (std::size_t k = 0; k < eps_.size(); ++k) {
    sigma_h[k] = B_[k].cwiseProduct(history(k) - c_e_ * eps_[k]);
  }
  add_viscous_forces(disc_, trial, sigma_h, cB_, r, K);
}

std::pair<double, double> StrainRateHistory::max_added_stiffness() const {
  double se = 0.0, bt = 0.0;
  for (const Vector6d& c : cB_) {
    se = std::max(se, c.head<3>().maxCoeff());
    bt = std::max(bt, c.tail<3>().maxCoeff());
  }
  return {se, bt};
}

void StrainRateHistory::advance(const State& state) {
  const std::vector<Vector6d> e1 = strains(state);
  for (std::size_t k = 0; k < e1.size(); ++k) {
    const Vector6d et1 = c_e_ * (e1[k] - eps_[k]) + history(k);
    a_eps_[k] = (et1 - eps_t_[k] - h_ * (1.0 - ap_.gamma) * a_eps_[k]) / (h_ * ap_.gamma);
    eps_t_[k] = et1;
    eps_[k] = e1[k];
  }
}

void StrainRateHistory::set_time_step(double dt_s) {
  h_ = dt_s;
  c_e_ = ap_.gamma / (ap_.beta * dt_s);
  for (std::size_t k = 0; k < B_.size(); ++k) cB_[k] = c_e_ * B_[k];
}

}  // namespace tcasim::beam_fe::damping
