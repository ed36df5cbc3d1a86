#pragma once
/// The inextensible, unshearable elastica of a cantilever under a tip dead load (the closed
/// form behind [Mattiasson1981]'s table), to about 1e-14, with Carlson's elliptic integrals.
///
/// Rod along +z from a clamp at the origin, load P along +x at the tip, k = P L^2 / EI.
/// With theta(s) the tangent's angle from z toward x: EI theta'' + P cos theta = 0,
/// theta(0) = 0, theta'(L) = 0; the first integral and the substitution
/// 1 + sin theta = 2 m sin^2 phi (m = (1 + sin alpha) / 2, alpha = theta(L)) give
/// ([Mattiasson1981]; K. E. Bisshopp, D. C. Drucker, Q. Appl. Math. 3:272-275, 1945)
///   sqrt(k) = K(m) - F(phi0, m),      sin phi0 = 1 / sqrt(2 m),
///   x(L) / L = 1 - 2 (E(m) - E(phi0, m)) / sqrt(k),   z(L) / L = sqrt(2 sin alpha / k),
/// with F, E the incomplete elliptic integrals of the first and second kind (parameter m).

namespace tcasim::test_support {

/// Carlson's symmetric integrals R_F(x, y, z) and R_D(x, y, z) by the duplication theorem
/// (B. C. Carlson, "Numerical computation of real or complex elliptic integrals", Numer.
/// Algorithms 10:13-26, 1995): iterated until the arguments agree to 1e-3 relative, then the
/// fifth-order series (its truncation error is of order (1e-3)^6).
double carlson_rf(double x, double y, double z);
double carlson_rd(double x, double y, double z);

/// Incomplete elliptic integrals of the first and second kind, amplitude phi in [0, pi/2],
/// parameter m in [0, 1): F = s R_F(c^2, 1 - m s^2, 1), E = F - m s^3 R_D(c^2, 1 - m s^2, 1) / 3
/// (s = sin phi, c = cos phi; DLMF 19.25.5, 19.25.9).
double elliptic_f(double phi, double m);
double elliptic_e(double phi, double m);

/// Tip of the inextensible cantilever elastica under a tip dead load k = P L^2 / EI > 0.
struct ElasticaTip {
  double deflection;  ///< x(L) / L (along the load)
  double axial;       ///< z(L) / L (along the undeformed axis)
  double rotation;    ///< alpha = theta(L) [rad]
};
/// Solves sqrt(k) = K(m) - F(phi0, m) for m in (1/2, 1) by bisection to round-off.
ElasticaTip cantilever_elastica_tip(double k);

}  // namespace tcasim::test_support
