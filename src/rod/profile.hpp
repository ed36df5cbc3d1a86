#pragma once
/// A scalar that varies along the body's reference arc length s: constant, or piecewise
/// linear between listed points (docs/scenario-format.md "Profiles along the body"). A
/// repeated s is a jump: the value on its left, then the one on its right.
#include <vector>

namespace tcasim::rod {

/// Which one-sided limit a profile gives at a jump (elsewhere both are the value).
enum class Side { kRight, kLeft };

class Profile {
 public:
  /// The constant 0.
  Profile() = default;
  /// A constant.
  explicit Profile(double constant) : v_{constant} {}
  /// Piecewise linear through (s_m[i], values[i]). Throws DomainError unless the sizes match,
  /// there are at least two points, s never decreases and no s appears more than twice (a
  /// scenario reader checks this first with key-named messages).
  Profile(std::vector<double> s_m, std::vector<double> values);

  bool is_constant() const { return s_.empty(); }
  /// The value at s (s outside the listed range: the nearest end value); at a jump the limit
  /// from `side` (kRight: the value after the jump, the default).
  double value(double s, Side side = Side::kRight) const;
  /// d value / ds at s: the slope of the piece holding s on `side` (0 for a constant and
  /// outside the listed range).
  double slope(double s, Side side = Side::kRight) const;
  /// Smallest and largest listed value (the extremes of a piecewise linear function).
  double min_value() const;
  double max_value() const;
  /// The listed s, without repeats (empty for a constant).
  std::vector<double> breakpoints() const;
  /// Whether the left and right limits differ at s.
  bool jumps_at(double s) const { return value(s, Side::kLeft) != value(s, Side::kRight); }
  const std::vector<double>& s_m() const { return s_; }
  const std::vector<double>& values() const { return v_; }

 private:
  /// The index lo of the piece [s_[lo], s_[lo + 1]] (s_[lo] < s_[lo + 1]) holding s on
  /// `side`; -1 before the first s, -2 after the last (never for a constant).
  long piece(double s, Side side) const;

  std::vector<double> s_;       // empty: constant v_[0]
  std::vector<double> v_{0.0};  // one value (constant) or one per s
};

}  // namespace tcasim::rod
