// Spline routings (docs/scenario-format.md "General routing and string extent"): a string
// through listed offsets, joined by straight pieces or a C2 natural cubic spline.
#include <algorithm>
#include <vector>

#include "rod/model.hpp"

namespace tcasim::rod {

void Routing::build_spline() {
  const std::size_t n = knot_s_m.size();
  knot_curvatures.assign(n, Eigen::Vector2d::Zero());
  if (linear || n < 3) return;  // two points: the straight line between them
  // Natural cubic spline ([Press2007] Sec. 3.3): M_0 = M_k = 0 and, for 0 < i < k,
  //   h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1}
  //     = 6 ((P_{i+1} - P_i)/h_i - (P_i - P_{i-1})/h_{i-1}),   h_i = s_{i+1} - s_i,
  // solved by the Thomas algorithm (diagonally dominant: no pivoting needed).
  std::vector<double> c(n, 0.0);
  std::vector<Eigen::Vector2d> d(n, Eigen::Vector2d::Zero());
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = knot_s_m[i] - knot_s_m[i - 1], h1 = knot_s_m[i + 1] - knot_s_m[i];
    const Eigen::Vector2d rhs = 6.0 * ((knot_offsets_m[i + 1] - knot_offsets_m[i]) / h1 -
                                       (knot_offsets_m[i] - knot_offsets_m[i - 1]) / h0);
    const double diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
    c[i] = h1 / diag;
    d[i] = (rhs - h0 * d[i - 1]) / diag;
  }
  for (std::size_t i = n - 2; i >= 1; --i) {
    knot_curvatures[i] = d[i] - c[i] * knot_curvatures[i + 1];
  }
}

std::size_t Routing::spline_piece(double s_m, Side side) const {
  // kRight: the piece [s_j, s_{j+1}) with s_j <= s; kLeft: (s_j, s_{j+1}] with s <= s_{j+1}.
  const auto it = side == Side::kRight ? std::upper_bound(knot_s_m.begin(), knot_s_m.end(), s_m)
                                       : std::lower_bound(knot_s_m.begin(), knot_s_m.end(), s_m);
  const long j = static_cast<long>(it - knot_s_m.begin()) - 1;
  return static_cast<std::size_t>(std::clamp(j, 0L, static_cast<long>(knot_s_m.size()) - 2));
}

Eigen::Vector3d Routing::spline_eval(double s_m, Side side, int derivative) const {
  const std::size_t j = spline_piece(s_m, side);
  const double h = knot_s_m[j + 1] - knot_s_m[j];
  const double a = knot_s_m[j + 1] - s_m, b = s_m - knot_s_m[j];
  const Eigen::Vector2d &P0 = knot_offsets_m[j], &P1 = knot_offsets_m[j + 1];
  const Eigen::Vector2d &M0 = knot_curvatures[j], &M1 = knot_curvatures[j + 1];
  // [Press2007] Eq. (3.3.3) and its derivatives, with a = s_{j+1} - s, b = s - s_j:
  //   r   = M0 a^3/(6h) + M1 b^3/(6h) + (P0/h - M0 h/6) a + (P1/h - M1 h/6) b
  //   r'  = -M0 a^2/(2h) + M1 b^2/(2h) + (P1 - P0)/h - (M1 - M0) h/6
  //   r'' = (M0 a + M1 b)/h
  Eigen::Vector2d v;
  if (derivative == 0) {
    v = (M0 * (a * a * a) + M1 * (b * b * b)) / (6.0 * h) + (P0 / h - M0 * (h / 6.0)) * a +
        (P1 / h - M1 * (h / 6.0)) * b;
  } else if (derivative == 1) {
    v = (M1 * (b * b) - M0 * (a * a)) / (2.0 * h) + (P1 - P0) / h - (M1 - M0) * (h / 6.0);
  } else {
    v = (M0 * a + M1 * b) / h;
  }
  return {v.x(), v.y(), 0.0};
}

}  // namespace tcasim::rod
