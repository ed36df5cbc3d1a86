// Where strings act on the body: their anchors inside the body (docs/scenario-format.md
// "String extent") and the interior knots of spline routings, the knots they add to both
// solvers' discretizations.
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

namespace {
/// The interior spline knots strictly inside (0, L) of the routings `pick` selects.
template <class Pick>
std::vector<double> spline_knots(const RodModel& m, Pick pick) {
  std::vector<double> s;
  for (const Actuator& a : m.actuators) {
    if (a.routing.type != Routing::Type::kSpline || !pick(a.routing)) continue;
    const std::vector<double>& k = a.routing.knot_s_m;
    for (std::size_t j = 1; j + 1 < k.size(); ++j) {
      if (k[j] > 0.0 && k[j] < m.length_m) s.push_back(k[j]);
    }
  }
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}
}  // namespace

std::vector<double> RodModel::routing_knots() const {
  return spline_knots(*this, [](const Routing&) { return true; });
}

std::vector<double> RodModel::routing_kinks() const {
  return spline_knots(*this, [](const Routing& r) { return r.kinked(); });
}

std::vector<double> RodModel::interior_knots() const {
  std::vector<double> s = breakpoints();
  const std::vector<double> a = anchor_points();
  s.insert(s.end(), a.begin(), a.end());
  const std::vector<double> r = routing_knots();
  s.insert(s.end(), r.begin(), r.end());
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
