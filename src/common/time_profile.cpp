#include "common/time_profile.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim {
namespace {

std::string sub(std::string_view key, std::string_view k) {
  std::string s(key);
  s += '.';
  s += k;
  return s;
}

void require_finite(double x, const std::string& key) {
  require(std::isfinite(x), key, x, "must be a finite number");
}

}  // namespace

TimeProfile TimeProfile::constant(double value, std::string_view key) {
  require_finite(value, std::string(key));
  TimeProfile p;
  p.kind_ = Kind::kConstant;
  p.a_ = value;
  return p;
}

TimeProfile TimeProfile::table(std::vector<double> t_s, std::vector<double> values,
                               std::string_view key) {
  const std::string tk = sub(key, "t_s"), vk = sub(key, "values");
  require(!t_s.empty(), tk, "[]", "must have at least one point");
  require(values.size() == t_s.size(), vk, "(" + std::to_string(values.size()) + " values)",
          "must have as many entries as t_s (" + std::to_string(t_s.size()) + ")");
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    const std::string ti = tk + "[" + std::to_string(i) + "]";
    require_finite(t_s[i], ti);
    require_finite(values[i], vk + "[" + std::to_string(i) + "]");
    if (i > 0) {
      require(t_s[i] > t_s[i - 1], ti, t_s[i],
              "must be greater than " + tk + "[" + std::to_string(i - 1) +
                  "] = " + format_value(t_s[i - 1]) + " (t_s strictly increasing)");
    }
  }
  TimeProfile p;
  p.kind_ = Kind::kTable;
  p.t_ = std::move(t_s);
  p.v_ = std::move(values);
  return p;
}

TimeProfile TimeProfile::step(double t0_s, double before, double after, std::string_view key) {
  const std::string k = sub(key, "step");
  require_finite(t0_s, sub(k, "t_s"));
  require_finite(before, sub(k, "before"));
  require_finite(after, sub(k, "after"));
  TimeProfile p;
  p.kind_ = Kind::kStep;
  p.t0_ = t0_s;
  p.a_ = before;
  p.b_ = after;
  return p;
}

TimeProfile TimeProfile::pwm(double period_s, double duty, double high, double low,
                             std::string_view key) {
  const std::string k = sub(key, "pwm");
  require_finite(period_s, sub(k, "period_s"));
  require(period_s > 0.0, sub(k, "period_s"), period_s, "must be positive");
  require_finite(duty, sub(k, "duty"));
  require(duty >= 0.0 && duty <= 1.0, sub(k, "duty"), duty, "must lie in [0, 1]");
  require_finite(high, sub(k, "high"));
  require_finite(low, sub(k, "low"));
  TimeProfile p;
  p.kind_ = Kind::kPwm;
  p.period_ = period_s;
  p.duty_ = duty;
  p.a_ = high;
  p.b_ = low;
  return p;
}

TimeProfile TimeProfile::sine(double mean, double amplitude, double frequency_Hz, double phase_rad,
                              std::string_view key) {
  const std::string k = sub(key, "sine");
  require_finite(mean, sub(k, "mean"));
  require_finite(amplitude, sub(k, "amplitude"));
  require_finite(frequency_Hz, sub(k, "frequency_Hz"));
  require(frequency_Hz >= 0.0, sub(k, "frequency_Hz"), frequency_Hz, "must be >= 0");
  require_finite(phase_rad, sub(k, "phase_deg"));
  TimeProfile p;
  p.kind_ = Kind::kSine;
  p.a_ = mean;
  p.b_ = amplitude;
  p.frequency_ = frequency_Hz;
  p.phase_ = phase_rad;
  return p;
}

double TimeProfile::value(double t) const {
  switch (kind_) {
    case Kind::kConstant:
      return a_;
    case Kind::kTable: {
      if (t <= t_.front()) return v_.front();
      if (t >= t_.back()) return v_.back();
      // First point above t: t_[i - 1] < t < t_[i] (t equal to a point returns it exactly).
      const std::size_t i =
          static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin());
      if (t == t_[i - 1]) return v_[i - 1];
      const double w = (t - t_[i - 1]) / (t_[i] - t_[i - 1]);
      return v_[i - 1] + w * (v_[i] - v_[i - 1]);
    }
    case Kind::kStep:
      return t <= t0_ ? a_ : b_;
    case Kind::kPwm: {
      if (duty_ >= 1.0) return a_;
      if (duty_ <= 0.0) return b_;
      // Phase x in [0, 1); x = 0 is the end of the previous period's low part.
      const double c = t / period_;
      const double x = c - std::floor(c);
      return (x > 0.0 && x <= duty_) ? a_ : b_;
    }
    case Kind::kSine:
      return a_ + b_ * std::sin(2.0 * units::kPi * frequency_ * t + phase_);
  }
  return a_;
}

double TimeProfile::right_limit(double t) const {
  switch (kind_) {
    case Kind::kStep:
      return t < t0_ ? a_ : b_;
    case Kind::kPwm: {
      if (duty_ >= 1.0) return a_;
      if (duty_ <= 0.0) return b_;
      const double c = t / period_;
      const double x = c - std::floor(c);
      return x < duty_ ? a_ : b_;
    }
    default:
      return value(t);  // continuous
  }
}

bool TimeProfile::is_constant() const { return min_value() == max_value(); }

double TimeProfile::min_value() const {
  switch (kind_) {
    case Kind::kConstant:
      return a_;
    case Kind::kTable:
      return *std::min_element(v_.begin(), v_.end());
    case Kind::kStep:
      return std::min(a_, b_);
    case Kind::kPwm:
      return duty_ >= 1.0 ? a_ : duty_ <= 0.0 ? b_ : std::min(a_, b_);
    case Kind::kSine:
      return frequency_ == 0.0 ? value(0.0) : a_ - std::abs(b_);
  }
  return a_;
}

double TimeProfile::max_value() const {
  switch (kind_) {
    case Kind::kConstant:
      return a_;
    case Kind::kTable:
      return *std::max_element(v_.begin(), v_.end());
    case Kind::kStep:
      return std::max(a_, b_);
    case Kind::kPwm:
      return duty_ >= 1.0 ? a_ : duty_ <= 0.0 ? b_ : std::max(a_, b_);
    case Kind::kSine:
      return frequency_ == 0.0 ? value(0.0) : a_ + std::abs(b_);
  }
  return a_;
}

std::vector<double> TimeProfile::breakpoints(double t_begin, double t_end) const {
  std::vector<double> out;
  if (!(t_end > t_begin)) return out;
  const auto inside = [&](double t) { return t > t_begin && t <= t_end; };
  switch (kind_) {
    case Kind::kConstant:
    case Kind::kSine:
      break;
    case Kind::kTable:
      for (double t : t_) {
        if (inside(t)) out.push_back(t);
      }
      break;
    case Kind::kStep:
      if (inside(t0_) && a_ != b_) out.push_back(t0_);
      break;
    case Kind::kPwm: {
      if (duty_ <= 0.0 || duty_ >= 1.0 || a_ == b_) break;
      const double k_lo = std::floor(t_begin / period_) - 1.0;
      const double k_hi = std::ceil(t_end / period_) + 1.0;
      if (2.0 * (k_hi - k_lo) > static_cast<double>(kMaxBreakpoints)) {
        throw DomainError("TimeProfile::breakpoints: a PWM of period " + format_value(period_) +
                          " s has more than " + std::to_string(kMaxBreakpoints) +
                          " switching times in (" + format_value(t_begin) + ", " +
                          format_value(t_end) + "] s");
      }
      for (double k = k_lo; k <= k_hi; k += 1.0) {
        const double on = k * period_, off = (k + duty_) * period_;
        if (inside(on)) out.push_back(on);
        if (inside(off)) out.push_back(off);
      }
      break;
    }
  }
  return out;
}

TimeProfile TimeProfile::affine(double offset, double scale) const {
  TimeProfile p = *this;
  const auto f = [&](double v) { return offset + scale * v; };
  switch (kind_) {
    case Kind::kConstant:
      p.a_ = f(a_);
      break;
    case Kind::kTable:
      for (double& v : p.v_) v = f(v);
      break;
    case Kind::kStep:
    case Kind::kPwm:
      p.a_ = f(a_);
      p.b_ = f(b_);
      break;
    case Kind::kSine:
      p.a_ = f(a_);
      p.b_ = scale * b_;
      break;
  }
  return p;
}

}  // namespace tcasim
