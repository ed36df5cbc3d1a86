#include "rod/profile.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "common/error.hpp"

namespace tcasim::rod {

Profile::Profile(std::vector<double> s_m, std::vector<double> values) {
  if (s_m.size() != values.size() || s_m.size() < 2) {
    throw DomainError("Profile: needs at least two points and as many values as s (" +
                      std::to_string(s_m.size()) + " s, " + std::to_string(values.size()) +
                      " values)");
  }
  for (std::size_t i = 1; i < s_m.size(); ++i) {
    if (!(s_m[i] >= s_m[i - 1])) throw DomainError("Profile: s must never decrease");
    if (i >= 2 && s_m[i] == s_m[i - 2]) {
      throw DomainError("Profile: an s may appear at most twice (a jump)");
    }
  }
  s_ = std::move(s_m);
  v_ = std::move(values);
}

long Profile::piece(double s, Side side) const {
  if (side == Side::kRight) {
    // The last listed s <= s: the piece that starts there holds s.
    const auto it = std::upper_bound(s_.begin(), s_.end(), s);
    if (it == s_.begin()) return -1;
    if (it == s_.end()) return -2;
    return static_cast<long>(it - s_.begin()) - 1;
  }
  // The first listed s >= s: the piece that ends there holds s.
  const auto it = std::lower_bound(s_.begin(), s_.end(), s);
  if (it == s_.begin()) return -1;
  if (it == s_.end()) return -2;
  return static_cast<long>(it - s_.begin()) - 1;
}

double Profile::value(double s, Side side) const {
  if (s_.empty()) return v_[0];
  const long k = piece(s, side);
  if (k == -1) return v_.front();
  if (k == -2) return v_.back();
  const auto lo = static_cast<std::size_t>(k);
  const double t = (s - s_[lo]) / (s_[lo + 1] - s_[lo]);
  return v_[lo] + t * (v_[lo + 1] - v_[lo]);
}

double Profile::slope(double s, Side side) const {
  if (s_.empty()) return 0.0;
  const long k = piece(s, side);
  if (k < 0) return 0.0;
  const auto lo = static_cast<std::size_t>(k);
  return (v_[lo + 1] - v_[lo]) / (s_[lo + 1] - s_[lo]);
}

double Profile::min_value() const { return *std::min_element(v_.begin(), v_.end()); }
double Profile::max_value() const { return *std::max_element(v_.begin(), v_.end()); }

std::vector<double> Profile::breakpoints() const {
  std::vector<double> b = s_;
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

}  // namespace tcasim::rod
