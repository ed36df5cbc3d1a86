// Element kernel of the Simo-Reissner beam: residual and consistent tangent.
//
// Chain of variables in one element (n = order + 1 nodes, reference node r):
//   increments theta = (dp_a, dtheta_a)_a            (6n, material rotation increments)
//   -> u = (y_a = R_r^T (p_a - p_r), psi_a = log(R_r^T R_a))  (6n, y_r = psi_r = 0)
//   -> at a Gauss point g = (y', psi, psi') = G u     (9, linear in u)
//   -> strains eps = (nu, omega) = (exp(psi)^T y', Jr(psi) psi')
//   -> energy density W(eps) = 1/2 |nu - e3|^2_Knu + 1/2 |omega - omega*|^2_Komega
//                              + sum_i c_i T_i |q_i|,  q_i = nu + omega x r_i + r_i'.
// The residual is the gradient of the element energy in the chart theta at 0:
//   r = B^T G^T F^T sigma, B = du/dtheta, F = deps/dg, sigma = dW/deps.
// The tangent is the derivative of r under the update R <- R exp(eta):
//   K = B^T H_u B + (second derivatives of u(theta) contracted with dE/du)
//       + 1/2 hat(r_theta,a) on each node's rotation block,
// the last term from exp(eta) exp(theta) = exp(eta + theta + eta x theta / 2 + ...).
// Second derivatives of the strain map in psi and first derivatives of Jr^-1 come from
// forward-mode dual numbers (dual.hpp); everything else is closed form.
#include <cmath>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/dual.hpp"
#include "common/so3.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using D3 = ad::Dual<double, 3>;
using DD3 = ad::Dual<D3, 3>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;

/// Lagrange shape functions on xi in [-1, 1] with equally spaced nodes.
void shape(int order, double xi, double* N, double* dN_dxi) {
  if (order == 1) {
    N[0] = 0.5 * (1.0 - xi);
    N[1] = 0.5 * (1.0 + xi);
    dN_dxi[0] = -0.5;
    dN_dxi[1] = 0.5;
  } else {
    N[0] = 0.5 * xi * (xi - 1.0);
    N[1] = 1.0 - xi * xi;
    N[2] = 0.5 * xi * (xi + 1.0);
    dN_dxi[0] = xi - 0.5;
    dN_dxi[1] = -2.0 * xi;
    dN_dxi[2] = xi + 0.5;
  }
}

/// A rotation vector as duals seeded with the unit directions.
template <class S>
ad::V3<S> seeded(const Vector3d& v);
template <>
ad::V3<D3> seeded<D3>(const Vector3d& v) {
  ad::V3<D3> r;
  for (int k = 0; k < 3; ++k) {
    r[k] = D3(v[k]);
    r[k].d[k] = 1.0;
  }
  return r;
}
template <>
ad::V3<DD3> seeded<DD3>(const Vector3d& v) {
  ad::V3<DD3> r;
  for (int k = 0; k < 3; ++k) {
    r[k] = DD3(v[k]);
    r[k].v.d[k] = 1.0;
    r[k].d[k] = D3(1.0);
  }
  return r;
}

/// Jacobian d(vec)/dpsi of a D3-valued 3-vector.
Matrix3d jacobian(const ad::V3<D3>& v) {
  Matrix3d J;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) J(i, k) = v[i].d[k];
  return J;
}

template <class S>
ad::V3<S> rotation_operator(const ad::V3<S>& x, const S& t2, const S& alpha, const S& beta, const Vector3d& v) {
  const S xv = x[0] * v[0] + x[1] * v[1] + x[2] * v[2];
  const ad::V3<S> xc = {x[1] * v[2] - x[2] * v[1], x[2] * v[0] - x[0] * v[2], x[0] * v[1] - x[1] * v[0]};
  ad::V3<S> r;
  for (int i = 0; i < 3; ++i) r[i] = v[i] + alpha * xc[i] + beta * (x[i] * xv - t2 * v[i]);
  return r;
}

template <int kOrder>
void element_kernel(const rod::RodModel& model, const std::vector<double>& xi,
                    const std::vector<double>& weight, double h_m_, const State& state, int e,
                    const std::vector<double>& tensions_N, bool with_tangent, ElementEvaluation& out) {
  constexpr int n = kOrder + 1;
  constexpr int nu_dofs = 6 * n;
  constexpr int order_ = kOrder;
  using VectorU = Eigen::Matrix<double, nu_dofs, 1>;
  using MatrixU = Eigen::Matrix<double, nu_dofs, nu_dofs>;
  const int first = e * order_;
  const int ref = order_ == 1 ? 0 : 1;  // reference node: a node, so psi_ref = 0 exactly
  const Eigen::Quaterniond q_ref = state.q_WB[first + ref];
  const Matrix3d R_ref = q_ref.toRotationMatrix();
  const Vector3d K_nu = model.shear_extension_stiffness();
  const Vector3d K_omega = model.bending_torsion_stiffness();
  const Vector3d omega_ref = model.reference_curvature_B_1_m;
  const std::size_t n_act = model.actuators.size();

  // Node map u(theta): y_a = R_r^T (p_a - p_r), psi_a = log(R_r^T R_a).
  std::array<Vector3d, n> y, psi;
  std::array<Matrix3d, n> A;                   // Jr^-1(psi_a)
  std::array<std::array<Matrix3d, 3>, n> dA;   // dJr^-1/dpsi_k
  for (int a = 0; a < n; ++a) {
    // Relative to the reference node (y' is unchanged since sum_a N_a' = 0): keeps the
    // moment rows free of |p| times the force round-off.
    y[a] = R_ref.transpose() * (state.p_W_m[first + a] - state.p_W_m[first + ref]);
    psi[a] = a == ref ? Vector3d::Zero() : so3::log(q_ref.conjugate() * state.q_WB[first + a]);
    A[a].setIdentity();
    if (a == ref) continue;
    // A = Jr^-1(psi) = I + K/2 + d K^2 (K = hat(psi)); dA/dpsi_k = hat(e_k)/2 + (dd/dpsi_k) K^2
    // + d (hat(e_k) K + K hat(e_k)), with dd/dpsi_k from dual numbers.
    const ad::V3<D3> x = seeded<D3>(psi[a]);
    const D3 d = ad::coefficients(ad::dot(x, x)).d;
    const Matrix3d K = so3::hat(psi[a]);
    A[a] = Matrix3d::Identity() + 0.5 * K + d.v * K * K;
    for (int k = 0; k < 3; ++k) {
      const Matrix3d Ek = so3::hat(Vector3d::Unit(k));
      dA[a][k] = 0.5 * Ek + d.d[k] * K * K + d.v * (Ek * K + K * Ek);
    }
  }

  VectorU grad_u = VectorU::Zero();
  MatrixU hess_u = MatrixU::Zero();
  out.lengths_m.assign(n_act, 0.0);
  std::vector<VectorU> dl_u(n_act, VectorU::Zero());

  double N[3], dN_dxi[3];
  for (std::size_t g = 0; g < xi.size(); ++g) {
    shape(order_, xi[g], N, dN_dxi);
    const double wj = weight[g] * 0.5 * h_m_;
    const double s_m = state.s_m[first] + 0.5 * (xi[g] + 1.0) * h_m_;
    double dN[3];
    for (int a = 0; a < n; ++a) dN[a] = dN_dxi[a] * 2.0 / h_m_;
    Vector3d yp = Vector3d::Zero(), ps = Vector3d::Zero(), pp = Vector3d::Zero();
    for (int a = 0; a < n; ++a) {
      yp += dN[a] * y[a];
      ps += N[a] * psi[a];
      pp += dN[a] * psi[a];
    }
    // Strains and their psi-derivatives: nu = exp(psi)^T y', omega = Jr(psi) psi'.
    const ad::V3<D3> psd = seeded<D3>(ps);
    const D3 t2d = ad::dot(psd, psd);
    const ad::Coefficients<D3> kd = ad::coefficients(t2d);
    const ad::V3<D3> nu_d = rotation_operator(psd, t2d, -kd.a, kd.b, yp);  // exp(psi)^T y'
    const ad::V3<D3> om_d = rotation_operator(psd, t2d, -kd.b, kd.c, pp);  // Jr(psi) psi'
    Vector3d nu, omega;
    for (int i = 0; i < 3; ++i) {
      nu[i] = nu_d[i].v;
      omega[i] = om_d[i].v;
    }
    const Matrix3d E_val = so3::exp(ps);
    const Matrix3d Jr_val = so3::right_jacobian(ps);
    // Constitutive law and strings: sigma = dW/deps, C = d2W/deps2.
    // [Pawlowski2019] Eqs. (11)-(12): n_B = K_nu (nu - e3), m_B = K_omega (omega - omega*).
    Vector6d sigma;
    sigma.head<3>() = K_nu.cwiseProduct(nu - Vector3d::UnitZ());
    sigma.tail<3>() = K_omega.cwiseProduct(omega - omega_ref);
    Matrix6d C = Matrix6d::Zero();
    C.diagonal() << K_nu, K_omega;
    std::vector<Vector6d> dl_eps(n_act);
    for (std::size_t i = 0; i < n_act; ++i) {
      const rod::Routing& route = model.actuators[i].routing;
      const Vector3d r = route.r(s_m);
      // [Pawlowski2019] Eq. (19): q = nu + omega x r + r'.
      const Vector3d q = nu + omega.cross(r) + route.dr(s_m);
      const double q_norm = q.norm();
      const Vector3d qh = q / q_norm;
      Eigen::Matrix<double, 3, 6> Q;
      Q << Matrix3d::Identity(), -so3::hat(r);
      dl_eps[i] = Q.transpose() * qh;  // (qh, r x qh)
      out.lengths_m[i] += wj * q_norm;
      const double cT = model.actuators[i].count * tensions_N[i];
      sigma += cT * dl_eps[i];
      const Matrix3d P = (Matrix3d::Identity() - qh * qh.transpose()) / q_norm;
      if (with_tangent) C += cT * Q.transpose() * P * Q;
    }
    const Vector3d s_nu = sigma.head<3>(), s_om = sigma.tail<3>();

    // F = deps/d(y', psi, psi').
    Eigen::Matrix<double, 6, 9> F = Eigen::Matrix<double, 6, 9>::Zero();
    F.block<3, 3>(0, 0) = E_val.transpose();
    F.block<3, 3>(0, 3) = jacobian(nu_d);
    F.block<3, 3>(3, 3) = jacobian(om_d);
    F.block<3, 3>(3, 6) = Jr_val;

    // Gather matrix G: g = G u.
    Eigen::Matrix<double, 9, nu_dofs> Gm = Eigen::Matrix<double, 9, nu_dofs>::Zero();
    for (int a = 0; a < n; ++a) {
      Gm.template block<3, 3>(0, 3 * a) = dN[a] * Matrix3d::Identity();
      Gm.template block<3, 3>(3, 3 * n + 3 * a) = N[a] * Matrix3d::Identity();
      Gm.template block<3, 3>(6, 3 * n + 3 * a) = dN[a] * Matrix3d::Identity();
    }
    const Vector9d grad_g = F.transpose() * sigma;
    grad_u.noalias() += wj * Gm.transpose() * grad_g;
    for (std::size_t i = 0; i < n_act; ++i) dl_u[i].noalias() += wj * Gm.transpose() * (F.transpose() * dl_eps[i]);
    if (!with_tangent) continue;

    // S = sum_k sigma_k d2 eps_k / dg2: only blocks involving psi are non-zero.
    Matrix9d S = Matrix9d::Zero();
    const Matrix3d S_yp_psi = jacobian(rotation_operator(psd, t2d, kd.a, kd.b, s_nu));  // d(exp(psi) s_nu)/dpsi
    const Matrix3d S_pp_psi = jacobian(rotation_operator(psd, t2d, kd.b, kd.c, s_om));  // d(Jr^T s_om)/dpsi
    S.block<3, 3>(0, 3) = S_yp_psi;
    S.block<3, 3>(3, 0) = S_yp_psi.transpose();
    S.block<3, 3>(6, 3) = S_pp_psi;
    S.block<3, 3>(3, 6) = S_pp_psi.transpose();
    {
      // s(psi) = s_nu . exp(psi)^T y' + s_om . Jr(psi) psi' written with scalar triple
      // products (a x b . c = a . (b x c)) so the nested duals see few operations:
      //   exp(psi)^T y' = y' - a psi x y' + b (psi (psi . y') - t^2 y'),
      //   Jr(psi) psi'  = psi' - b psi x psi' + c (psi (psi . psi') - t^2 psi').
      const ad::V3<DD3> x = seeded<DD3>(ps);
      const ad::Coefficients<DD3> k = ad::coefficients(ad::dot(x, x));
      const Vector3d y_x_s = yp.cross(s_nu), p_x_s = pp.cross(s_om);
      auto dot_const = [&](const Vector3d& v) { return x[0] * v[0] + x[1] * v[1] + x[2] * v[2]; };
      const DD3 t2 = ad::dot(x, x);
      const DD3 s = -1.0 * k.a * dot_const(y_x_s) +
                    k.b * (dot_const(s_nu) * dot_const(yp) - t2 * s_nu.dot(yp)) -
                    k.b * dot_const(p_x_s) +
                    k.c * (dot_const(s_om) * dot_const(pp) - t2 * s_om.dot(pp));
      for (int j = 0; j < 3; ++j)
        for (int m = 0; m < 3; ++m) S(3 + j, 3 + m) = s.d[j].d[m];
    }
    const Matrix9d hess_g = F.transpose() * C * F + S;
    // hess_u += wj G^T hess_g G, with G's blocks dN_a I (y'), N_a I (psi), dN_a I (psi').
    for (int a = 0; a < n; ++a) {
      const Eigen::Matrix<double, 3, 9> ya = wj * dN[a] * hess_g.template topRows<3>();
      const Eigen::Matrix<double, 3, 9> pa =
          wj * (N[a] * hess_g.template middleRows<3>(3) + dN[a] * hess_g.template bottomRows<3>());
      for (int b = 0; b < n; ++b) {
        hess_u.template block<3, 3>(3 * a, 3 * b) += dN[b] * ya.template leftCols<3>();
        hess_u.template block<3, 3>(3 * a, 3 * n + 3 * b) +=
            N[b] * ya.template middleCols<3>(3) + dN[b] * ya.template rightCols<3>();
        hess_u.template block<3, 3>(3 * n + 3 * a, 3 * b) += dN[b] * pa.template leftCols<3>();
        hess_u.template block<3, 3>(3 * n + 3 * a, 3 * n + 3 * b) +=
            N[b] * pa.template middleCols<3>(3) + dN[b] * pa.template rightCols<3>();
      }
    }
  }

  // B = du/dtheta at theta = 0, with y_a = exp(-theta_r) R_r^T (p_a + dp_a - p_r - dp_r)
  // (y_r = 0 identically) and psi_a = log(exp(-theta_r) exp(psi_a) exp(theta_a)).
  MatrixU B = MatrixU::Zero();
  const int phr = 6 * ref + 3;  // column of the reference node's rotation increment
  const int dr = 6 * ref;       // column of the reference node's position increment
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    B.template block<3, 3>(3 * a, 6 * a) = R_ref.transpose();
    B.template block<3, 3>(3 * a, dr) = -R_ref.transpose();
    B.template block<3, 3>(3 * a, phr) = so3::hat(y[a]);
    B.template block<3, 3>(3 * n + 3 * a, 6 * a + 3) = A[a];
    B.template block<3, 3>(3 * n + 3 * a, phr) = -A[a].transpose();
  }
  out.residual = B.transpose() * grad_u;
  out.length_gradients.resize(n_act);
  for (std::size_t i = 0; i < n_act; ++i) out.length_gradients[i] = B.transpose() * dl_u[i];
  if (!with_tangent) return;
  // K = B^T H B using the block sparsity of B (at most three 3x3 blocks per block row).
  MatrixU HB = MatrixU::Zero();
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    const Eigen::Matrix<double, nu_dofs, 3> HyR = hess_u.template middleCols<3>(3 * a) * R_ref.transpose();
    HB.template middleCols<3>(6 * a) += HyR;
    HB.template middleCols<3>(dr) -= HyR;
    HB.template middleCols<3>(phr).noalias() += hess_u.template middleCols<3>(3 * a) * so3::hat(y[a]);
    HB.template middleCols<3>(6 * a + 3).noalias() += hess_u.template middleCols<3>(3 * n + 3 * a) * A[a];
    HB.template middleCols<3>(phr).noalias() -= hess_u.template middleCols<3>(3 * n + 3 * a) * A[a].transpose();
  }
  MatrixU K = MatrixU::Zero();
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    const Eigen::Matrix<double, 3, nu_dofs> RHy = R_ref * HB.template middleRows<3>(3 * a);
    K.template middleRows<3>(6 * a) += RHy;
    K.template middleRows<3>(dr) -= RHy;
    K.template middleRows<3>(phr).noalias() += so3::hat(y[a]).transpose() * HB.template middleRows<3>(3 * a);
    K.template middleRows<3>(6 * a + 3).noalias() += A[a].transpose() * HB.template middleRows<3>(3 * n + 3 * a);
    K.template middleRows<3>(phr).noalias() -= A[a] * HB.template middleRows<3>(3 * n + 3 * a);
  }
  // Second derivatives of u(theta) contracted with dE/du.
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    const Vector3d gy = grad_u.template segment<3>(3 * a);
    K.template block<3, 3>(phr, phr) +=
        0.5 * (gy * y[a].transpose() + y[a] * gy.transpose()) - gy.dot(y[a]) * Matrix3d::Identity();
    const Matrix3d Hrd = so3::hat(gy) * R_ref.transpose();
    K.template block<3, 3>(phr, 6 * a) += Hrd;
    K.template block<3, 3>(phr, dr) -= Hrd;
    K.template block<3, 3>(6 * a, phr) += Hrd.transpose();
    K.template block<3, 3>(dr, phr) -= Hrd.transpose();
    // psi_a = log(exp(-theta_r) exp(psi_a) exp(theta_a)): dpsi = A dtheta_a - A^T dtheta_r
    // at 0, with A = Jr^-1(psi_a) and Jl^-1(psi) = Jr^-1(psi)^T.
    const Vector3d gp = grad_u.template segment<3>(3 * n + 3 * a);
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
    K.template block<3, 3>(pha, pha) += Haa;
    K.template block<3, 3>(phr, phr) += Hrr;
    K.template block<3, 3>(pha, phr) += Har;
    K.template block<3, 3>(phr, pha) += Har.transpose();
  }
  // exp(eta) exp(theta) = exp(eta + theta + eta x theta / 2 + ...): the residual's
  // derivative along the update adds hat(r_rot)/2 per node.
  for (int a = 0; a < n; ++a) {
    const Vector3d g_rot = out.residual.template segment<3>(6 * a + 3);
    K.template block<3, 3>(6 * a + 3, 6 * a + 3) += 0.5 * so3::hat(g_rot);
  }
  out.tangent = K;
}

}  // namespace

ElementEvaluation Discretization::element(const State& state, int e,
                                          const std::vector<double>& tensions_N) const {
  ElementEvaluation out;
  evaluate_element(state, e, tensions_N, true, out);
  return out;
}

void Discretization::evaluate_element(const State& state, int e, const std::vector<double>& tensions_N,
                                      bool with_tangent, ElementEvaluation& out) const {
  if (order_ == 1) {
    element_kernel<1>(*model_, quad_.xi, quad_.weight, h_m_, state, e, tensions_N, with_tangent, out);
  } else {
    element_kernel<2>(*model_, quad_.xi, quad_.weight, h_m_, state, e, tensions_N, with_tangent, out);
  }
}

std::vector<PointStrain> Discretization::strains(const State& state) const {
  std::vector<PointStrain> out;
  const int n = order_ + 1;
  const int ref = order_ == 1 ? 0 : 1;
  double N[3], dN_dxi[3];
  for (int e = 0; e < elements_; ++e) {
    const int first = e * order_;
    const Eigen::Quaterniond q_ref = state.q_WB[first + ref];
    const Matrix3d R_ref = q_ref.toRotationMatrix();
    std::vector<Vector3d> y(n), psi(n);
    for (int a = 0; a < n; ++a) {
      y[a] = R_ref.transpose() * (state.p_W_m[first + a] - state.p_W_m[first + ref]);
      psi[a] = a == ref ? Vector3d::Zero() : so3::log(q_ref.conjugate() * state.q_WB[first + a]);
    }
    for (std::size_t g = 0; g < quad_.xi.size(); ++g) {
      shape(order_, quad_.xi[g], N, dN_dxi);
      Vector3d yp = Vector3d::Zero(), ps = Vector3d::Zero(), pp = Vector3d::Zero();
      for (int a = 0; a < n; ++a) {
        yp += dN_dxi[a] * 2.0 / h_m_ * y[a];
        ps += N[a] * psi[a];
        pp += dN_dxi[a] * 2.0 / h_m_ * psi[a];
      }
      out.push_back({state.s_m[first] + 0.5 * (quad_.xi[g] + 1.0) * h_m_,
                     so3::exp(ps).transpose() * yp, so3::right_jacobian(ps) * pp});
    }
  }
  return out;
}

}  // namespace tcasim::beam_fe
