#pragma once
/// The element interpolation's shape functions and the Gauss-Legendre rules of the beam FE
/// (element kernel, dead loads, mass, damping, probes, energies).
#include <vector>

namespace tcasim::beam_fe::internal {

/// Lagrange shape functions of order 1 or 2 on xi in [-1, 1] (equally spaced nodes) and their
/// xi-derivatives. Inline: the element kernel calls it at every quadrature point.
inline void shape(int order, double xi, double* N, double* dN_dxi) {
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

/// Gauss-Legendre rule with `points` (1, 2 or 3) points xi on [-1, 1] and weights w.
void gauss_rule(int points, std::vector<double>& xi, std::vector<double>& w);

}  // namespace tcasim::beam_fe::internal
