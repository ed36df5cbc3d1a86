// Strings anchored inside the body (docs/conventions.md "Strings anchored inside the body"):
// the anchors as knots of the piecewise shooting IVP, and which strings run along each piece.
// The jump at a knot (RodRhs::strain_jump) keeps the total section wrench, rod plus the
// strings that cross the section, continuous; at an anchor the set of strings changes, which
// is the anchor's point force and moment on the body.
#include <algorithm>

#include "cosserat/problem.hpp"

namespace tcasim::cosserat::internal {

void RodProblem::add_anchor_knots() {
  const std::vector<double> anchors = model.anchor_points();
  if (anchors.empty()) return;
  if (knots.empty()) knots = {0.0, 0.5 * L, L};  // as a varying body's (L/2: bending radius)
  std::vector<double> all = knots;
  all.insert(all.end(), anchors.begin(), anchors.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  knots = all;
  knot_jumps.clear();
  for (double s : knots) {
    knot_jumps.push_back(std::binary_search(anchors.begin(), anchors.end(), s) ||
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
