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
// The strain map's coefficients a, b, c, d are functions of t^2 = |psi|^2 only; their first
// and second t^2-derivatives come from scalar nested dual numbers (common/dual.hpp), and every
// psi-derivative (first derivatives of the strains and of Jr^-1, second derivatives of the
// strain map contracted with the stresses) is written in closed form from them.
#include <cmath>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/internal/node_map.hpp"
#include "beam_fe/internal/quadrature.hpp"
#include "common/dual.hpp"
#include "common/lie_series.hpp"
#include "common/so3.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;
using internal::shape;

/// The coefficients a, b, c, d (common/lie_series.hpp) at t2 = |psi|^2 and their first and second
/// derivatives with respect to t2, from a scalar nested dual seeded on t2.
struct CoefficientJet {
  so3::Coefficients<double> f, df, ddf;
};
CoefficientJet coefficient_jet(double t2) {
  using S1 = ad::Dual<double, 1>;
  using S2 = ad::Dual<S1, 1>;
  S2 x(t2);
  x.v.d[0] = 1.0;
  x.d[0] = S1(1.0);
  const so3::Coefficients<S2> k = so3::coefficients(x);
  CoefficientJet j;
  auto unpack = [](const S2& y, double& f, double& df, double& ddf) {
    f = y.v.v;
    df = y.v.d[0];
    ddf = y.d[0].d[0];
  };
  unpack(k.a, j.f.a, j.df.a, j.ddf.a);
  unpack(k.b, j.f.b, j.df.b, j.ddf.b);
  unpack(k.c, j.f.c, j.df.c, j.ddf.c);
  unpack(k.d, j.f.d, j.df.d, j.ddf.d);
  return j;
}

/// v + alpha x × v + beta (x (x.v) - t2 v) with t2 = |x|^2: exp(x)^T v for (alpha, beta) =
/// (-a, b), exp(x) v for (a, b), Jr(x) v for (-b, c), Jr(x)^T v for (b, c).
Vector3d rotation_operator(const Vector3d& x, double t2, double alpha, double beta,
                           const Vector3d& v) {
  return v + alpha * x.cross(v) + beta * (x * x.dot(v) - t2 * v);
}
/// Its Jacobian in x, with dalpha, dbeta the t2-derivatives of alpha, beta:
///   2 alpha' (x × v) x^T - alpha hat(v) + 2 beta' (x (x.v) - t2 v) x^T
///   + beta ((x.v) I + x v^T - 2 v x^T).
Matrix3d rotation_operator_jacobian(const Vector3d& x, double t2, double alpha, double dalpha,
                                    double beta, double dbeta, const Vector3d& v) {
  const double xv = x.dot(v);
  Matrix3d J = (2.0 * dalpha * x.cross(v) + 2.0 * dbeta * (x * xv - t2 * v)) * x.transpose();
  J -= alpha * so3::hat(v);
  J += beta * (xv * Matrix3d::Identity() + x * v.transpose() - 2.0 * v * x.transpose());
  return J;
}
/// Hessian in x of f(t2) (x.u): 4 f'' (x.u) x x^T + 2 f' ((x.u) I + x u^T + u x^T).
void add_linear_term_hessian(Matrix3d& H, const Vector3d& x, double f1, double f2,
                             const Vector3d& u) {
  const double xu = x.dot(u);
  H += 4.0 * f2 * xu * x * x.transpose();
  H += 2.0 * f1 * (xu * Matrix3d::Identity() + x * u.transpose() + u * x.transpose());
}
/// Hessian in x of g(t2) Q, Q = (x.v)(x.w) - t2 (v.w), grad Q = v (x.w) + w (x.v) - 2 (v.w) x:
///   4 g'' Q x x^T + 2 g' (Q I + x gradQ^T + gradQ x^T) + g (v w^T + w v^T - 2 (v.w) I).
void add_quadratic_term_hessian(Matrix3d& H, const Vector3d& x, double t2, double g, double g1,
                                double g2, const Vector3d& v, const Vector3d& w) {
  const double xv = x.dot(v), xw = x.dot(w), vw = v.dot(w);
  const double Q = xv * xw - t2 * vw;
  const Vector3d gQ = v * xw + w * xv - 2.0 * vw * x;
  H += 4.0 * g2 * Q * x * x.transpose();
  H += 2.0 * g1 * (Q * Matrix3d::Identity() + x * gQ.transpose() + gQ * x.transpose());
  H += g * (v * w.transpose() + w * v.transpose() - 2.0 * vw * Matrix3d::Identity());
}

/// The element interpolation at a Gauss point: y' = sum_a N_a' y_a, psi = sum_a N_a psi_a,
/// psi' = sum_a N_a' psi_a (N, dN = dN/ds of the n nodes).
template <int n>
void interpolate(const double* N, const double* dN, const std::array<Vector3d, n>& y,
                 const std::array<Vector3d, n>& psi, Vector3d& yp, Vector3d& ps, Vector3d& pp) {
  yp = ps = pp = Vector3d::Zero();
  for (int a = 0; a < n; ++a) {
    yp += dN[a] * y[a];
    ps += N[a] * psi[a];
    pp += dN[a] * psi[a];
  }
}

template <int kOrder>
void element_kernel(const rod::RodModel& model, const rod::SectionStiffness& base_stiffness,
                    const Vector3d& base_omega_star, const std::vector<double>& xi,
                    const std::vector<double>& weight, double h_m_, const State& state, int e,
                    const std::vector<double>& tensions_N, bool with_tangent,
                    ElementEvaluation& out) {
  constexpr int n = kOrder + 1;
  constexpr int nu_dofs = 6 * n;
  constexpr int order_ = kOrder;
  using VectorU = Eigen::Matrix<double, nu_dofs, 1>;
  using MatrixU = Eigen::Matrix<double, nu_dofs, nu_dofs>;
  const int first = e * order_;
  const int ref = order_ == 1 ? 0 : 1;  // reference node: a node, so psi_ref = 0 exactly
  const Eigen::Quaterniond q_ref = state.q_WB[first + ref];
  const Matrix3d R_ref = q_ref.toRotationMatrix();
  // A body that varies along s: the properties at each quadrature point (inside the element,
  // so never at a breakpoint, where the mesh has a node).
  const bool uniform = model.uniform_body();
  Vector3d K_nu = base_stiffness.shear_extension;
  Vector3d K_omega = base_stiffness.bending_torsion;
  Vector3d omega_ref = base_omega_star;
  const std::size_t n_act = model.actuators.size();
  // A string anchored inside the body runs along the elements of its span only (the mesh
  // has nodes at the anchors): its potential c T l over the span.
  const double s_mid_m = state.s_m[first] + 0.5 * h_m_;
  std::vector<char> runs(n_act, 1);
  for (std::size_t i = 0; i < n_act; ++i) {
    const rod::Actuator& a = model.actuators[i];
    runs[i] = a.span_start_m() < s_mid_m && s_mid_m < a.span_end_m(model.length_m);
  }

  // Node map u(theta): y_a = R_r^T (p_a - p_r), psi_a = log(R_r^T R_a).
  std::array<Vector3d, n> y, psi;
  std::array<Matrix3d, n> A;                  // Jr^-1(psi_a)
  std::array<std::array<Matrix3d, 3>, n> dA;  // dJr^-1/dpsi_k
  internal::node_coordinates(state, first, n, ref, q_ref, R_ref, y.data(), psi.data());
  for (int a = 0; a < n; ++a) {
    A[a].setIdentity();
    if (a == ref) continue;
    // A = Jr^-1(psi) and dA/dpsi_k, with d and d'(t2) from dual numbers.
    const CoefficientJet jet = coefficient_jet(psi[a].squaredNorm());
    internal::inverse_right_jacobian(psi[a], jet.f.d, jet.df.d, A[a], dA[a]);
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
    if (!uniform) {
      const rod::SectionStiffness k = model.stiffness_at(s_m);
      K_nu = k.shear_extension;
      K_omega = k.bending_torsion;
      omega_ref = model.reference_curvature_at(s_m);
    }
    double dN[3];
    for (int a = 0; a < n; ++a) dN[a] = dN_dxi[a] * 2.0 / h_m_;
    Vector3d yp, ps, pp;
    interpolate<n>(N, dN, y, psi, yp, ps, pp);
    // Strains and their psi-derivatives: nu = exp(psi)^T y', omega = Jr(psi) psi'.
    const double t2 = ps.squaredNorm();
    const CoefficientJet jet = coefficient_jet(t2);
    const so3::Coefficients<double>& k0 = jet.f;
    const so3::Coefficients<double>& k1 = jet.df;
    const Vector3d nu = rotation_operator(ps, t2, -k0.a, k0.b, yp);     // exp(psi)^T y'
    const Vector3d omega = rotation_operator(ps, t2, -k0.b, k0.c, pp);  // Jr(psi) psi'
    const Matrix3d Kp = so3::hat(ps);
    const Matrix3d Kp2 = Kp * Kp;
    const Matrix3d E_val = Matrix3d::Identity() + k0.a * Kp + k0.b * Kp2;   // exp(psi)
    const Matrix3d Jr_val = Matrix3d::Identity() - k0.b * Kp + k0.c * Kp2;  // Jr(psi)
    // Constitutive law and strings: sigma = dW/deps, C = d2W/deps2.
    // [Pawlowski2019] Eqs. (11)-(12): n_B = K_nu (nu - e3), m_B = K_omega (omega - omega*).
    Vector6d sigma;
    sigma.head<3>() = K_nu.cwiseProduct(nu - Vector3d::UnitZ());
    sigma.tail<3>() = K_omega.cwiseProduct(omega - omega_ref);
    Matrix6d C = Matrix6d::Zero();
    C.diagonal() << K_nu, K_omega;
    std::vector<Vector6d> dl_eps(n_act);
    for (std::size_t i = 0; i < n_act; ++i) {
      if (!runs[i]) {
        dl_eps[i].setZero();
        continue;
      }
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
    F.block<3, 3>(0, 3) = rotation_operator_jacobian(ps, t2, -k0.a, -k1.a, k0.b, k1.b, yp);
    F.block<3, 3>(3, 3) = rotation_operator_jacobian(ps, t2, -k0.b, -k1.b, k0.c, k1.c, pp);
    F.block<3, 3>(3, 6) = Jr_val;

    // Gather matrix G: g = G u.
    Eigen::Matrix<double, 9, nu_dofs> Gm = Eigen::Matrix<double, 9, nu_dofs>::Zero();
    for (int a = 0; a < n; ++a) {
      Gm.template block<3, 3>(0, 3 * a) = dN[a] * Matrix3d::Identity();
      Gm.template block<3, 3>(3, 3 * n + 3 * a) = N[a] * Matrix3d::Identity();
      Gm.template block<3, 3>(6, 3 * n + 3 * a) = dN[a] * Matrix3d::Identity();
    }
    const Vector9d grad_g = F.transpose().lazyProduct(sigma);
    grad_u.noalias() += Gm.transpose().lazyProduct(wj * grad_g);
    for (std::size_t i = 0; i < n_act; ++i)
      dl_u[i].noalias() += Gm.transpose().lazyProduct(wj * F.transpose().lazyProduct(dl_eps[i]));
    if (!with_tangent) continue;

    // S = sum_k sigma_k d2 eps_k / dg2: only blocks involving psi are non-zero.
    Matrix9d S = Matrix9d::Zero();
    // d(exp(psi) s_nu)/dpsi and d(Jr(psi)^T s_om)/dpsi.
    const Matrix3d S_yp_psi = rotation_operator_jacobian(ps, t2, k0.a, k1.a, k0.b, k1.b, s_nu);
    const Matrix3d S_pp_psi = rotation_operator_jacobian(ps, t2, k0.b, k1.b, k0.c, k1.c, s_om);
    S.block<3, 3>(0, 3) = S_yp_psi;
    S.block<3, 3>(3, 0) = S_yp_psi.transpose();
    S.block<3, 3>(6, 3) = S_pp_psi;
    S.block<3, 3>(3, 6) = S_pp_psi.transpose();
    {
      // Hessian in psi of s(psi) = s_nu . exp(psi)^T y' + s_om . Jr(psi) psi', written with
      // scalar triple products (a x b . c = a . (b x c)):
      //   s = -a psi.(y' x s_nu) + b ((psi.s_nu)(psi.y') - t2 s_nu.y')
      //       - b psi.(psi' x s_om) + c ((psi.s_om)(psi.psi') - t2 s_om.psi') + const.
      const so3::Coefficients<double>& k2 = jet.ddf;
      Matrix3d H = Matrix3d::Zero();
      add_linear_term_hessian(H, ps, -k1.a, -k2.a, yp.cross(s_nu));
      add_quadratic_term_hessian(H, ps, t2, k0.b, k1.b, k2.b, s_nu, yp);
      add_linear_term_hessian(H, ps, -k1.b, -k2.b, pp.cross(s_om));
      add_quadratic_term_hessian(H, ps, t2, k0.c, k1.c, k2.c, s_om, pp);
      S.block<3, 3>(3, 3) = H;
    }
    const Eigen::Matrix<double, 9, 6> FtC = F.transpose().lazyProduct(C);
    const Matrix9d hess_g = FtC.lazyProduct(F) + S;
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
  internal::node_map_jacobian(n, ref, R_ref, y.data(), A.data(), B);
  const int phr = 6 * ref + 3;  // column of the reference node's rotation increment
  const int dr = 6 * ref;       // column of the reference node's position increment
  out.residual = B.transpose().lazyProduct(grad_u);
  out.length_gradients.resize(n_act);
  for (std::size_t i = 0; i < n_act; ++i)
    out.length_gradients[i] = B.transpose().lazyProduct(dl_u[i]);
  if (!with_tangent) return;
  // K = B^T H B using the block sparsity of B (at most three 3x3 blocks per block row).
  MatrixU HB = MatrixU::Zero();
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    const Eigen::Matrix<double, nu_dofs, 3> HyR =
        hess_u.template middleCols<3>(3 * a).lazyProduct(R_ref.transpose());
    HB.template middleCols<3>(6 * a) += HyR;
    HB.template middleCols<3>(dr) -= HyR;
    HB.template middleCols<3>(phr).noalias() +=
        hess_u.template middleCols<3>(3 * a).lazyProduct(so3::hat(y[a]));
    HB.template middleCols<3>(6 * a + 3).noalias() +=
        hess_u.template middleCols<3>(3 * n + 3 * a).lazyProduct(A[a]);
    HB.template middleCols<3>(phr).noalias() -=
        hess_u.template middleCols<3>(3 * n + 3 * a).lazyProduct(A[a].transpose());
  }
  MatrixU K = MatrixU::Zero();
  for (int a = 0; a < n; ++a) {
    if (a == ref) continue;
    const Eigen::Matrix<double, 3, nu_dofs> RHy =
        R_ref.lazyProduct(HB.template middleRows<3>(3 * a));
    K.template middleRows<3>(6 * a) += RHy;
    K.template middleRows<3>(dr) -= RHy;
    K.template middleRows<3>(phr).noalias() +=
        so3::hat(y[a]).transpose().lazyProduct(HB.template middleRows<3>(3 * a));
    K.template middleRows<3>(6 * a + 3).noalias() +=
        A[a].transpose().lazyProduct(HB.template middleRows<3>(3 * n + 3 * a));
    K.template middleRows<3>(phr).noalias() -=
        A[a].lazyProduct(HB.template middleRows<3>(3 * n + 3 * a));
  }
  // Second derivatives of u(theta) contracted with dE/du.
  internal::add_node_map_hessian(n, ref, R_ref, y.data(), A.data(), dA.data(), grad_u, K);
  // exp(eta) exp(theta) = exp(eta + theta + eta x theta / 2 + ...): the residual's
  // derivative along the update adds hat(r_rot)/2 per node.
  for (int a = 0; a < n; ++a) {
    const Vector3d g_rot = out.residual.template segment<3>(6 * a + 3);
    K.template block<3, 3>(6 * a + 3, 6 * a + 3) += 0.5 * so3::hat(g_rot);
  }
  out.tangent = K;
}

/// The element's share of each string length alone: the arithmetic of element_kernel's
/// lengths_m (the same nodal map, strains and Eq. (19) integrand, bit for bit) without the
/// stresses, gradients and tangent (make_result needs the lengths only).
template <int kOrder>
void element_string_lengths(const rod::RodModel& model, const std::vector<double>& xi,
                            const std::vector<double>& weight, double h_m_, const State& state,
                            int e, std::vector<double>& lengths_m) {
  constexpr int n = kOrder + 1;
  constexpr int order_ = kOrder;
  const int first = e * order_;
  const int ref = order_ == 1 ? 0 : 1;
  const Eigen::Quaterniond q_ref = state.q_WB[first + ref];
  const Matrix3d R_ref = q_ref.toRotationMatrix();
  const std::size_t n_act = model.actuators.size();
  const double s_mid_m = state.s_m[first] + 0.5 * h_m_;
  std::array<Vector3d, n> y, psi;
  internal::node_coordinates(state, first, n, ref, q_ref, R_ref, y.data(), psi.data());
  std::vector<double> element_share(n_act, 0.0);
  double N[3], dN_dxi[3];
  for (std::size_t g = 0; g < xi.size(); ++g) {
    shape(order_, xi[g], N, dN_dxi);
    const double wj = weight[g] * 0.5 * h_m_;
    const double s_m = state.s_m[first] + 0.5 * (xi[g] + 1.0) * h_m_;
    double dN[3];
    for (int a = 0; a < n; ++a) dN[a] = dN_dxi[a] * 2.0 / h_m_;
    Vector3d yp, ps, pp;
    interpolate<n>(N, dN, y, psi, yp, ps, pp);
    const double t2 = ps.squaredNorm();
    const CoefficientJet jet = coefficient_jet(t2);
    const so3::Coefficients<double>& k0 = jet.f;
    // [Pawlowski2019] Eq. (19): q = nu + omega x r + r', nu = exp(psi)^T y', omega = Jr(psi) psi'.
    const Vector3d nu = rotation_operator(ps, t2, -k0.a, k0.b, yp);
    const Vector3d omega = rotation_operator(ps, t2, -k0.b, k0.c, pp);
    for (std::size_t i = 0; i < n_act; ++i) {
      const rod::Actuator& a = model.actuators[i];
      if (!(a.span_start_m() < s_mid_m && s_mid_m < a.span_end_m(model.length_m))) continue;
      const Vector3d q = nu + omega.cross(a.routing.r(s_m)) + a.routing.dr(s_m);
      element_share[i] += wj * q.norm();
    }
  }
  for (std::size_t i = 0; i < n_act; ++i) lengths_m[i] += element_share[i];
}

}  // namespace

ElementEvaluation Discretization::element(const State& state, int e,
                                          const std::vector<double>& tensions_N) const {
  ElementEvaluation out;
  evaluate_element(state, e, tensions_N, true, out);
  return out;
}

void Discretization::evaluate_element(const State& state, int e,
                                      const std::vector<double>& tensions_N, bool with_tangent,
                                      ElementEvaluation& out) const {
  if (order_ == 1) {
    element_kernel<1>(*model_, base_stiffness_, base_omega_star_, quad_.xi, quad_.weight,
                      element_h_m_[static_cast<std::size_t>(e)], state, e, tensions_N, with_tangent,
                      out);
  } else {
    element_kernel<2>(*model_, base_stiffness_, base_omega_star_, quad_.xi, quad_.weight,
                      element_h_m_[static_cast<std::size_t>(e)], state, e, tensions_N, with_tangent,
                      out);
  }
}

std::vector<double> Discretization::string_lengths(const State& state) const {
  std::vector<double> l(model_->actuators.size(), 0.0);
  for (int e = 0; e < elements_; ++e) {
    const double h_e = element_h_m_[static_cast<std::size_t>(e)];
    if (order_ == 1) {
      element_string_lengths<1>(*model_, quad_.xi, quad_.weight, h_e, state, e, l);
    } else {
      element_string_lengths<2>(*model_, quad_.xi, quad_.weight, h_e, state, e, l);
    }
  }
  return l;
}

std::vector<PointStrain> Discretization::strains(const State& state) const {
  std::vector<PointStrain> out;
  const int n = order_ + 1;
  const int ref = order_ == 1 ? 0 : 1;
  double N[3], dN_dxi[3];
  for (int e = 0; e < elements_; ++e) {
    const int first = e * order_;
    const double h_e = element_h_m_[static_cast<std::size_t>(e)];
    const Eigen::Quaterniond q_ref = state.q_WB[first + ref];
    const Matrix3d R_ref = q_ref.toRotationMatrix();
    std::vector<Vector3d> y(n), psi(n);
    internal::node_coordinates(state, first, n, ref, q_ref, R_ref, y.data(), psi.data());
    for (std::size_t g = 0; g < quad_.xi.size(); ++g) {
      shape(order_, quad_.xi[g], N, dN_dxi);
      Vector3d yp = Vector3d::Zero(), ps = Vector3d::Zero(), pp = Vector3d::Zero();
      for (int a = 0; a < n; ++a) {
        yp += dN_dxi[a] * 2.0 / h_e * y[a];
        ps += N[a] * psi[a];
        pp += dN_dxi[a] * 2.0 / h_e * psi[a];
      }
      out.push_back({state.s_m[first] + 0.5 * (quad_.xi[g] + 1.0) * h_e,
                     so3::exp(ps).transpose() * yp, so3::right_jacobian(ps) * pp});
    }
  }
  return out;
}

}  // namespace tcasim::beam_fe
