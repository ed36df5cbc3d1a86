#include "cosserat/internal/planar.hpp"

#include <cassert>
#include <cmath>

#include "common/dual.hpp"

namespace tcasim::cosserat::planar {
namespace {

/// The library's dual number (common/dual.hpp) with N directional derivatives.
template <int N>
using Dual = ad::Dual<double, N>;
using ad::sqrt;
using std::sqrt;

/// Unit string direction qh = q / |q| in the plane, q = nu + omega x r = (nu_x, nu_z - kappa rho).
template <class S>
struct StringDirection {
  S q_norm, inv_norm, hx, hz;
};

template <class S>
inline StringDirection<S> direction(const S& nu_x, const S& nu_z, const S& kappa, double rho) {
  const S qz = nu_z - kappa * rho;
  const S qn = sqrt(nu_x * nu_x + qz * qz);
  const S inv = 1.0 / qn;
  return {qn, inv, nu_x * inv, qz * inv};
}

/// The planar RHS for any scalar type: S = double (the state) or Dual (its sensitivities).
/// cT[i] = c_i T_i of actuator i.
template <class S>
void evaluate(const Rod& P, const S* y, const S* cT, S* dy) {
  const S& c = y[kCS];
  const S& s = y[kCS + 1];
  const S& nu_x = y[kNu];
  const S& e_z = y[kNu + 1];  // nu_z - 1 (the state holds the deviation)
  const S nu_z = e_z + 1.0;
  const S& kappa = y[kKappa];
  // [Pawlowski2019] Eqs. (9)-(10) in the plane: n_B = (K_x nu_x, 0, K_z (nu_z - 1)); m_B is
  // along y, so omega x m_B = 0.
  const S n_x = P.kn_x * nu_x;
  const S n_z = P.kn_z * e_z;
  // R^T f_ext with R = R_WB0 Rot_y: Rot_y^T (f_x, 0, f_z).
  const S f_x = c * P.f_x - s * P.f_z;
  const S f_z = s * P.f_x + c * P.f_z;
  // b_nu = -omega x n_B - R^T f_ext - sum g_i;  b_omega = -nu x n_B - sum r_i x g_i  (x, z; y).
  S b0 = -(kappa * n_z) - f_x;
  S b1 = kappa * n_x - f_z;
  S b2 = nu_x * n_z - nu_z * n_x;
  const int n = static_cast<int>(P.rho.size());
  S alpha[kMaxActuators], u0[kMaxActuators], u1[kMaxActuators], u2[kMaxActuators];
  for (int i = 0; i < n; ++i) {
    const double rho = P.rho[i];
    const StringDirection<S> q = direction(nu_x, nu_z, kappa, rho);
    dy[kDelta + i] = q.q_norm - P.length_ratio[i];  // delta_i' = |q_i| - L_i / L
    // g_i = c_i T_i omega x qh = c_i T_i kappa (h_z, 0, -h_x) (straight string);
    // (r_i x g_i)_y = -rho g_z.
    const S gk = cT[i] * kappa;
    b0 = b0 - gk * q.hz;
    b1 = b1 + gk * q.hx;
    b2 = b2 - rho * (gk * q.hx);
    // U_i A_i U_i^T in (nu_x, nu_z, omega_y): A_i = alpha_i (I - qh qh^T) acts in the plane as
    // alpha_i t t^T with t = (h_z, -h_x); U_i^T maps (z_nu, z_omega) to z_nu + z_omega x r_i,
    // so the block is alpha_i u_i u_i^T with u_i = (t_x, t_z, -rho t_z).
    alpha[i] = cT[i] * q.inv_norm;
    u0[i] = q.hz;
    u1[i] = -q.hx;
    u2[i] = rho * q.hx;
  }
  // M z = b with M = diag(K_x, K_z, K_omega_y) + sum_i alpha_i u_i u_i^T.
  const double d0 = 1.0 / P.kn_x, d1 = 1.0 / P.kn_z, d2 = 1.0 / P.kw_y;
  S z0 = d0 * b0, z1 = d1 * b1, z2 = d2 * b2;  // D^-1 b
  if (n == 1) {
    // Sherman-Morrison: z = D^-1 b - D^-1 u alpha (u . D^-1 b) / (1 + alpha u . D^-1 u);
    // det M = det D (1 + alpha u . D^-1 u), so the denominator vanishes exactly when M is
    // singular (a non-finite derivative then fails the IVP).
    const S v0 = d0 * u0[0], v1 = d1 * u1[0], v2 = d2 * u2[0];
    const S num = alpha[0] * (u0[0] * z0 + u1[0] * z1 + u2[0] * z2);
    const S den = 1.0 + alpha[0] * (u0[0] * v0 + u1[0] * v1 + u2[0] * v2);
    const S coef = num / den;
    z0 = z0 - coef * v0;
    z1 = z1 - coef * v1;
    z2 = z2 - coef * v2;
  } else if (n > 1) {
    // Symmetric 3x3 by its adjugate (Cramer's rule).
    S m00 = S() + P.kn_x, m11 = S() + P.kn_z, m22 = S() + P.kw_y;
    S m01 = S(), m02 = S(), m12 = S();
    for (int i = 0; i < n; ++i) {
      const S a0 = alpha[i] * u0[i], a1 = alpha[i] * u1[i], a2 = alpha[i] * u2[i];
      m00 = m00 + a0 * u0[i];
      m11 = m11 + a1 * u1[i];
      m22 = m22 + a2 * u2[i];
      m01 = m01 + a0 * u1[i];
      m02 = m02 + a0 * u2[i];
      m12 = m12 + a1 * u2[i];
    }
    const S c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22, c02 = m01 * m12 - m02 * m11;
    const S c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
    const S inv_det = 1.0 / (m00 * c00 + m01 * c01 + m02 * c02);
    z0 = (c00 * b0 + c01 * b1 + c02 * b2) * inv_det;
    z1 = (c01 * b0 + c11 * b1 + c12 * b2) * inv_det;
    z2 = (c02 * b0 + c12 * b1 + c22 * b2) * inv_det;
  }
  // [Pawlowski2019] Eqs. (7)-(8): q' = Rot_y (nu_x, 0, nu_z); Rot_y' = Rot_y hat(kappa e_y).
  dy[kQ] = c * nu_x + s * nu_z;
  dy[kQ + 1] = nu_z * c - s * nu_x;
  dy[kCS] = -(s * kappa);
  dy[kCS + 1] = c * kappa;
  dy[kNu] = z0;
  dy[kNu + 1] = z1;
  dy[kKappa] = z2;
  dy[kC] = y[kQ];
  dy[kC + 1] = y[kQ + 1];
}

/// Tip wrench residual for any scalar type (see tip_wrench).
template <class S>
void wrench(const Rod& P, double kappa_star, double F_x, double F_z, double M_y, const S* y,
            const S* cT, S out[3]) {
  const S& c = y[kCS];
  const S& s = y[kCS + 1];
  const S& nu_x = y[kNu];
  const S& e_z = y[kNu + 1];  // nu_z - 1
  const S nu_z = e_z + 1.0;
  const S& kappa = y[kKappa];
  // R^T F_e = Rot_y^T (F_x, 0, F_z); R^T M_e = (0, M_y, 0).
  S rn_x = P.kn_x * nu_x - (c * F_x - s * F_z);
  S rn_z = P.kn_z * e_z - (s * F_x + c * F_z);
  S rm_y = P.kw_y * (kappa - kappa_star) - M_y;
  for (int i = 0; i < static_cast<int>(P.rho.size()); ++i) {
    const StringDirection<S> q = direction(nu_x, nu_z, kappa, P.rho[i]);
    rn_x = rn_x + cT[i] * q.hx;
    rn_z = rn_z + cT[i] * q.hz;
    rm_y = rm_y - P.rho[i] * (cT[i] * q.hz);  // (r_i x qh)_y = -rho h_z
  }
  out[0] = rn_x;
  out[1] = rn_z;
  out[2] = rm_y;
}

/// Loads the state and its sensitivities into dual numbers, and the tensions with their
/// seeds (direction_of).
template <int N>
void load_duals(const Rod& P, int dim, int n_dir, const double* Y, Dual<N>* y, Dual<N>* cT) {
  for (int i = 0; i < dim; ++i) {
    y[i].v = Y[i];
    for (int j = 0; j < N; ++j) y[i].d[j] = j < n_dir ? Y[dim * (j + 1) + i] : 0.0;
  }
  for (int i = 0; i < static_cast<int>(P.rho.size()); ++i) {
    cT[i] = Dual<N>();
    cT[i].v = P.cT[i];
    if (P.direction_of[i] >= 0) cT[i].d[P.direction_of[i]] = P.count[i];
  }
}

template <int N>
void sens(const Rod& P, int dim, int n_dir, const double* Y, double* dY) {
  Dual<N> y[kDelta + kMaxActuators], dy[kDelta + kMaxActuators], cT[kMaxActuators];
  load_duals<N>(P, dim, n_dir, Y, y, cT);
  evaluate<Dual<N>>(P, y, cT, dy);
  for (int i = 0; i < dim; ++i) {
    dY[i] = dy[i].v;
    for (int j = 0; j < n_dir; ++j) dY[dim * (j + 1) + i] = dy[i].d[j];
  }
}

template <int N>
void wrench_sens(const Rod& P, double F_x, double F_z, int dim, int n_dir, const double* Y,
                 double* out) {
  Dual<N> y[kDelta + kMaxActuators], cT[kMaxActuators], w[3];
  load_duals<N>(P, dim, n_dir, Y, y, cT);
  wrench<Dual<N>>(P, 0.0, F_x, F_z, 0.0, y, cT, w);
  for (int j = 0; j < n_dir; ++j) {
    for (int k = 0; k < 3; ++k) out[3 * j + k] = w[k].d[j];
  }
}

}  // namespace

void rhs(const Rod& rod, const double* y, double* dy) {
  evaluate<double>(rod, y, rod.cT.data(), dy);
}

void rhs_sens(const Rod& rod, int dim, int n_dir, const double* Y, double* dY) {
  assert(n_dir <= kMaxDirections && static_cast<int>(rod.rho.size()) <= kMaxActuators);
  if (n_dir <= 4) {
    sens<4>(rod, dim, n_dir, Y, dY);
  } else {
    sens<kMaxDirections>(rod, dim, n_dir, Y, dY);
  }
}

void tip_wrench(const Rod& rod, double kappa_star, double F_x, double F_z, double M_y,
                const double* y, double out[3]) {
  wrench<double>(rod, kappa_star, F_x, F_z, M_y, y, rod.cT.data(), out);
}

void tip_wrench_sens(const Rod& rod, double F_x, double F_z, int dim, int n_dir, const double* Y,
                     double* out) {
  assert(n_dir <= kMaxDirections && static_cast<int>(rod.rho.size()) <= kMaxActuators);
  if (n_dir <= 4) {
    wrench_sens<4>(rod, F_x, F_z, dim, n_dir, Y, out);
  } else {
    wrench_sens<kMaxDirections>(rod, F_x, F_z, dim, n_dir, Y, out);
  }
}

}  // namespace tcasim::cosserat::planar
