// Strings anchored inside the body (docs/conventions.md "Strings anchored inside the body"):
// the anchors as knots of the piecewise shooting IVP, and which strings run along each piece.
// The jump at a knot (RodRhs::strain_jump) keeps the total section wrench, rod plus the
// strings that cross the section, continuous; at an anchor the set of strings changes, which
// is the anchor's point force and moment on the body.
#include <algorithm>

#include "cosserat/internal/problem.hpp"

namespace tcasim::cosserat::internal {

void RodProblem::add_string_knots() {
  const std::vector<double> anchors = model.anchor_points();
  const std::vector<double> routing = model.routing_knots();
  if (anchors.empty() && routing.empty()) return;
  // A spline routing's knots are piece ends too (docs/conventions.md "Spline routings"): r''
  // (cubic) or r' (linear) changes there; at a kink of a linear one the string's direction
  // jumps, which the strain jump turns into the string's point force on the body.
  const std::vector<double> kinks = model.routing_kinks();
  if (knots.empty()) knots = {0.0, 0.5 * L, L};  // as a varying body's (L/2: bending radius)
  std::vector<double> all = knots;
  all.insert(all.end(), anchors.begin(), anchors.end());
  all.insert(all.end(), routing.begin(), routing.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  knots = all;
  knot_jumps.clear();
  for (double s : knots) {
    knot_jumps.push_back(std::binary_search(anchors.begin(), anchors.end(), s) ||
                         std::binary_search(kinks.begin(), kinks.end(), s) ||
                         (!uniform && model.jumps_at(s)));
  }
  string_runs.assign(knots.size() - 1, std::vector<char>(static_cast<std::size_t>(n_act), 1));
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double mid = 0.5 * (knots[k] + knots[k + 1]);
    for (int i = 0; i < n_act; ++i) {
      string_runs[k][static_cast<std::size_t>(i)] = span_lo[i] < mid && mid < span_hi[i];
    }
  }
}

}  // namespace tcasim::cosserat::internal
