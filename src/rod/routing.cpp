// Where strings act on the body: their anchors inside the body (docs/scenario-format.md
// "String extent"), the knots they add to both solvers' discretizations.
#include <algorithm>
#include <vector>

#include "rod/model.hpp"

namespace tcasim::rod {

std::vector<double> RodModel::anchor_points() const {
  std::vector<double> s;
  for (const Actuator& a : actuators) {
    for (double x : {a.span_start_m(), a.span_end_m(length_m)}) {
      if (x > 0.0 && x < length_m) s.push_back(x);
    }
  }
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

std::vector<double> RodModel::interior_knots() const {
  std::vector<double> s = breakpoints();
  const std::vector<double> a = anchor_points();
  s.insert(s.end(), a.begin(), a.end());
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

bool RodModel::has_inner_anchors() const {
  for (const Actuator& a : actuators) {
    if (a.anchored_inside(length_m)) return true;
  }
  return false;
}

}  // namespace tcasim::rod
