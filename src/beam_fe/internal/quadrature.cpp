// Gauss-Legendre rules (beam_fe/internal/quadrature.hpp).
#include "beam_fe/internal/quadrature.hpp"

#include <cmath>

namespace tcasim::beam_fe::internal {

void gauss_rule(int points, std::vector<double>& xi, std::vector<double>& w) {
  if (points == 1) {
    xi = {0.0};
    w = {2.0};
  } else if (points == 2) {
    const double x = 1.0 / std::sqrt(3.0);
    xi = {-x, x};
    w = {1.0, 1.0};
  } else {
    const double x = std::sqrt(0.6);
    xi = {-x, 0.0, x};
    w = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  }
}

}  // namespace tcasim::beam_fe::internal
