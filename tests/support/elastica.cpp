#include "support/elastica.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tcasim::test_support {

namespace {
/// Duplication stops when every argument lies within this relative distance of their mean:
/// the series' remainder is then of order kAgreement^6 ~ 1e-18.
constexpr double kAgreement = 1e-3;
/// Safety bound on duplication steps (each divides the spread by about 4).
constexpr int kMaxDuplications = 60;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

// Carlson (1995), Algorithm 1 (R_F): x_{n+1} = (x_n + lambda_n) / 4 (same for y, z), lambda_n
// = sqrt(x y) + sqrt(y z) + sqrt(z x); with X = 1 - x_n / A_n (A_n their mean), Y, Z = -X - Y,
// E2 = X Y - Z^2, E3 = X Y Z: R_F = A_n^-1/2 (1 - E2/10 + E3/14 + E2^2/24 - 3 E2 E3/44).
double carlson_rf(double x, double y, double z) {
  if (!(x >= 0.0 && y >= 0.0 && z >= 0.0) || (x + y == 0.0) || (y + z == 0.0) || (z + x == 0.0)) {
    throw std::invalid_argument("carlson_rf: arguments must be >= 0, at most one zero");
  }
  for (int n = 0; n < kMaxDuplications; ++n) {
    const double A = (x + y + z) / 3.0;
    const double X = 1.0 - x / A, Y = 1.0 - y / A, Z = -X - Y;
    if (std::max({std::abs(X), std::abs(Y), std::abs(Z)}) < kAgreement) {
      const double E2 = X * Y - Z * Z, E3 = X * Y * Z;
      return (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0) / std::sqrt(A);
    }
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * sy + sy * sz + sz * sx;
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
  }
  throw std::runtime_error("carlson_rf: no convergence");
}

// Carlson (1995), Algorithm 4 with p = z (R_D): the same duplication plus the sum
// 3 sum_n 4^-n / (sqrt(z_n) (z_n + lambda_n)); A_n = (x + y + 3 z) / 5, X = 1 - x_n / A_n,
// Y = 1 - y_n / A_n, Z = -(X + Y) / 3, E2 = X Y - 6 Z^2, E3 = (3 X Y - 8 Z^2) Z,
// E4 = 3 (X Y - Z^2) Z^2, E5 = X Y Z^3:
// R_D = 4^-n A_n^-3/2 (1 - 3 E2/14 + E3/6 + 9 E2^2/88 - 3 E4/22 - 9 E2 E3/52 + 3 E5/26) + sum.
double carlson_rd(double x, double y, double z) {
  if (!(x >= 0.0 && y >= 0.0 && z > 0.0) || (x + y == 0.0)) {
    throw std::invalid_argument("carlson_rd: x, y >= 0 (not both zero), z > 0");
  }
  double sum = 0.0, scale = 1.0;
  for (int n = 0; n < kMaxDuplications; ++n) {
    const double A = (x + y + 3.0 * z) / 5.0;
    const double X = 1.0 - x / A, Y = 1.0 - y / A, Z = -(X + Y) / 3.0;
    if (std::max({std::abs(X), std::abs(Y), std::abs(Z)}) < kAgreement) {
      const double XY = X * Y, Z2 = Z * Z;
      const double E2 = XY - 6.0 * Z2, E3 = (3.0 * XY - 8.0 * Z2) * Z;
      const double E4 = 3.0 * (XY - Z2) * Z2, E5 = XY * Z2 * Z;
      const double series = 1.0 - 3.0 * E2 / 14.0 + E3 / 6.0 + 9.0 * E2 * E2 / 88.0 -
                            3.0 * E4 / 22.0 - 9.0 * E2 * E3 / 52.0 + 3.0 * E5 / 26.0;
      return scale * series / (A * std::sqrt(A)) + 3.0 * sum;
    }
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * sy + sy * sz + sz * sx;
    sum += scale / (sz * (z + lambda));
    scale *= 0.25;
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
  }
  throw std::runtime_error("carlson_rd: no convergence");
}

double elliptic_f(double phi, double m) {
  const double s = std::sin(phi), c = std::cos(phi);
  return s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
}

double elliptic_e(double phi, double m) {
  const double s = std::sin(phi), c = std::cos(phi);
  const double y = 1.0 - m * s * s;
  return s * carlson_rf(c * c, y, 1.0) - m * s * s * s * carlson_rd(c * c, y, 1.0) / 3.0;
}

ElasticaTip cantilever_elastica_tip(double k) {
  if (!(k > 0.0)) throw std::invalid_argument("cantilever_elastica_tip: k must be > 0");
  // g(m) = K(m) - F(phi0(m), m) increases from 0 (m = 1/2, phi0 = pi/2) to infinity (m -> 1).
  auto phi0 = [](double m) { return std::asin(1.0 / std::sqrt(2.0 * m)); };
  auto g = [&](double m) { return elliptic_f(0.5 * kPi, m) - elliptic_f(phi0(m), m); };
  const double target = std::sqrt(k);
  double lo = 0.5, hi = 1.0;
  while (hi - lo > 0.0) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (g(mid) < target ? lo : hi) = mid;
  }
  const double m = 0.5 * (lo + hi);
  const double sin_alpha = 2.0 * m - 1.0;
  ElasticaTip t;
  t.deflection = 1.0 - 2.0 * (elliptic_e(0.5 * kPi, m) - elliptic_e(phi0(m), m)) / target;
  t.axial = std::sqrt(2.0 * sin_alpha / k);
  t.rotation = std::asin(sin_alpha);
  return t;
}

}  // namespace tcasim::test_support
