#pragma once
/// A scalar function of time u(t) given by a scenario (docs/scenario-format.md, "Time
/// profiles"): constant, table (piecewise linear, constant outside), step, PWM or sine.
/// A value type: cheap to copy, immutable once built, validated on construction.
///
/// Jumps (step, PWM) take the value from the left at the jump time: u(t0) is the value
/// just before t0, the new value holds for t > t0. A static solve evaluates u(0), so a step
/// at t0 = 0 gives its `before` value and a PWM its `low` value (unless duty = 1): the
/// drive switches on at t = 0+.
#include <cstddef>
#include <string_view>
#include <vector>

namespace tcasim {

class TimeProfile {
 public:
  enum class Kind { kConstant, kTable, kStep, kPwm, kSine };

  /// The constant 0.
  TimeProfile() = default;

  /// The constant `value`. `key` names the value in errors (InputError unless finite).
  static TimeProfile constant(double value, std::string_view key = "profile");
  /// Piecewise linear through (t_s[i], values[i]), constant before the first and after the
  /// last point. Throws InputError (key `<key>.t_s[i]` / `<key>.values`) unless both are
  /// non-empty, of equal length, finite, and t_s strictly increasing.
  static TimeProfile table(std::vector<double> t_s, std::vector<double> values,
                           std::string_view key);
  /// `before` for t <= t0_s, `after` for t > t0_s (keys `<key>.step.t_s`, ...).
  static TimeProfile step(double t0_s, double before, double after, std::string_view key);
  /// Periodic from t = 0 with period P: `high` on (k P, k P + duty P], `low` on
  /// (k P + duty P, (k + 1) P] (high first). Requires P > 0 and duty in [0, 1].
  static TimeProfile pwm(double period_s, double duty, double high, double low,
                         std::string_view key);
  /// mean + amplitude sin(2 pi f t + phase). Requires f >= 0.
  static TimeProfile sine(double mean, double amplitude, double frequency_Hz, double phase_rad,
                          std::string_view key);

  Kind kind() const { return kind_; }
  /// u(t) (t in seconds, any finite t): at a jump, the value from the left.
  double value(double t_s) const;
  /// The limit of u from the right at t: equal to value(t) except at a jump, where it is the
  /// new value. An integrator stepping from t_n takes this at t_n, value(t) inside the step.
  double right_limit(double t_s) const;
  /// True if u(t) is the same for every t (a constant, a one-point table, a step with
  /// before = after, a PWM with duty 0 or 1 or high = low, a sine of zero amplitude or
  /// frequency).
  bool is_constant() const;
  /// Lower and upper bound of u over all t (both attained).
  double min_value() const;
  double max_value() const;
  /// The times in (t_begin_s, t_end_s] where u or du/dt jumps (table points, the step time,
  /// PWM switching times), increasing. An integrator that steps onto each of them never
  /// straddles a kink. Throws DomainError if there are more than kMaxBreakpoints.
  std::vector<double> breakpoints(double t_begin_s, double t_end_s) const;
  /// The profile a + b u(t) (e.g. degC -> K with a = 273.15, b = 1).
  TimeProfile affine(double offset, double scale) const;

  /// Largest number of breakpoints one call returns (a PWM of 1 us period over 10 s).
  static constexpr std::size_t kMaxBreakpoints = 10'000'000;

 private:
  Kind kind_ = Kind::kConstant;
  // kConstant: a_; kStep: t0_, a_ (before), b_ (after); kPwm: period_, duty_, a_ (high),
  // b_ (low); kSine: a_ (mean), b_ (amplitude), frequency_, phase_; kTable: t_, v_.
  double a_ = 0.0, b_ = 0.0;
  double t0_ = 0.0, period_ = 0.0, duty_ = 0.0, frequency_ = 0.0, phase_ = 0.0;
  std::vector<double> t_, v_;
};

}  // namespace tcasim
