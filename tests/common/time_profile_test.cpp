// Time profiles (common/time_profile.hpp): values, the left-continuous jump convention, bounds,
// breakpoints, and named errors for every rule.
#include "common/time_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim {
namespace {

/// Linear interpolation and sin() in double precision: only round-off remains.
constexpr double kRoundOff = 1e-14;

void expect_error(const std::function<void()>& f, const std::string& key,
                  const std::string& rule_part) {
  try {
    f();
    FAIL() << "expected InputError at " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.what();
  }
}

TEST(TimeProfile, DefaultAndConstantAreConstantEverywhere) {
  EXPECT_EQ(TimeProfile().value(3.0), 0.0);
  const TimeProfile c = TimeProfile::constant(2.5);
  EXPECT_EQ(c.value(-1.0), 2.5);
  EXPECT_EQ(c.value(1e6), 2.5);
  EXPECT_TRUE(c.is_constant());
  EXPECT_TRUE(c.breakpoints(0.0, 10.0).empty());
}

TEST(TimeProfile, TableIsPiecewiseLinearAndConstantOutside) {
  const TimeProfile p = TimeProfile::table({0.0, 1.0, 3.0}, {10.0, 20.0, 0.0}, "x");
  EXPECT_EQ(p.value(-5.0), 10.0);
  EXPECT_EQ(p.value(0.0), 10.0);
  EXPECT_NEAR(p.value(0.25), 12.5, kRoundOff);
  EXPECT_EQ(p.value(1.0), 20.0);
  EXPECT_NEAR(p.value(2.0), 10.0, kRoundOff);
  EXPECT_EQ(p.value(3.0), 0.0);
  EXPECT_EQ(p.value(99.0), 0.0);
  EXPECT_EQ(p.min_value(), 0.0);
  EXPECT_EQ(p.max_value(), 20.0);
  EXPECT_FALSE(p.is_constant());
  EXPECT_EQ(p.breakpoints(0.0, 3.0), (std::vector<double>{1.0, 3.0}));  // (t0, t1]
  EXPECT_EQ(TimeProfile::table({2.0}, {7.0}, "x").value(-1.0), 7.0);
  EXPECT_TRUE(TimeProfile::table({2.0}, {7.0}, "x").is_constant());
}

TEST(TimeProfile, StepTakesTheValueFromTheLeftAtItsTime) {
  const TimeProfile s = TimeProfile::step(0.0, 25.0, 90.0, "x");
  EXPECT_EQ(s.value(0.0), 25.0);  // a static solve at t = 0 sees `before`
  EXPECT_EQ(s.right_limit(0.0), 90.0);
  EXPECT_EQ(s.value(1e-12), 90.0);
  EXPECT_EQ(s.value(-1.0), 25.0);
  EXPECT_EQ(s.breakpoints(-1.0, 1.0), std::vector<double>{0.0});
  EXPECT_TRUE(s.breakpoints(0.0, 1.0).empty());  // 0 is not in (0, 1]
  EXPECT_EQ(TimeProfile::step(-1.0, 1.0, 2.0, "x").value(0.0), 2.0);
}

TEST(TimeProfile, PwmIsHighFirstAndLowAtItsSwitchOnInstants) {
  const TimeProfile p = TimeProfile::pwm(0.5, 0.25, 6.0, 1.0, "x");
  EXPECT_EQ(p.value(0.0), 1.0);  // left limit at t = 0: the end of a low phase
  EXPECT_EQ(p.right_limit(0.0), 6.0);
  EXPECT_EQ(p.value(0.01), 6.0);
  EXPECT_EQ(p.value(0.125), 6.0);  // end of the high phase (from the left)
  EXPECT_EQ(p.right_limit(0.125), 1.0);
  EXPECT_EQ(p.value(0.2), 1.0);
  EXPECT_EQ(p.value(0.51), 6.0);
  EXPECT_EQ(p.value(0.9), 1.0);
  EXPECT_EQ(p.min_value(), 1.0);
  EXPECT_EQ(p.max_value(), 6.0);
  const std::vector<double> b = p.breakpoints(0.0, 1.0);
  const std::vector<double> expected = {0.125, 0.5, 0.625, 1.0};
  ASSERT_EQ(b.size(), expected.size());
  for (std::size_t i = 0; i < b.size(); ++i) EXPECT_NEAR(b[i], expected[i], kRoundOff);
  // Duty 0 and 1 are constants without breakpoints.
  EXPECT_EQ(TimeProfile::pwm(1.0, 0.0, 6.0, 1.0, "x").value(0.3), 1.0);
  EXPECT_EQ(TimeProfile::pwm(1.0, 1.0, 6.0, 1.0, "x").value(0.0), 6.0);
  EXPECT_TRUE(TimeProfile::pwm(1.0, 1.0, 6.0, 1.0, "x").is_constant());
  EXPECT_TRUE(TimeProfile::pwm(1.0, 0.0, 6.0, 1.0, "x").breakpoints(0.0, 10.0).empty());
}

TEST(TimeProfile, PwmRefusesMoreBreakpointsThanItsLimit) {
  const TimeProfile p = TimeProfile::pwm(1e-9, 0.5, 1.0, 0.0, "x");
  EXPECT_THROW((void)p.breakpoints(0.0, 100.0), DomainError);
}

TEST(TimeProfile, SineHasMeanAmplitudeFrequencyAndPhase) {
  const TimeProfile s = TimeProfile::sine(2.0, 0.5, 4.0, units::deg_to_rad(30.0), "x");
  for (double t : {0.0, 0.01, 0.3, 1.7}) {
    EXPECT_NEAR(s.value(t), 2.0 + 0.5 * std::sin(2.0 * units::kPi * 4.0 * t + units::kPi / 6.0),
                kRoundOff);
  }
  EXPECT_NEAR(s.value(0.0), 2.25, kRoundOff);
  EXPECT_EQ(s.min_value(), 1.5);
  EXPECT_EQ(s.max_value(), 2.5);
  EXPECT_TRUE(s.breakpoints(0.0, 1.0).empty());
  EXPECT_TRUE(TimeProfile::sine(2.0, 0.5, 0.0, 0.0, "x").is_constant());
  EXPECT_TRUE(TimeProfile::sine(2.0, 0.0, 5.0, 0.0, "x").is_constant());
}

TEST(TimeProfile, AffineMapsEveryForm) {
  const double off = units::kZeroCelsius_K;
  EXPECT_EQ(TimeProfile::constant(90.0).affine(off, 1.0).value(0.0), units::degC_to_K(90.0));
  const TimeProfile t = TimeProfile::table({0.0, 1.0}, {0.0, 10.0}, "x").affine(1.0, 2.0);
  EXPECT_NEAR(t.value(0.5), 11.0, kRoundOff);
  EXPECT_EQ(TimeProfile::step(1.0, 1.0, 2.0, "x").affine(1.0, -1.0).value(2.0), -1.0);
  EXPECT_EQ(TimeProfile::pwm(1.0, 0.5, 3.0, 1.0, "x").affine(0.0, 2.0).value(0.25), 6.0);
  const TimeProfile s = TimeProfile::sine(1.0, 1.0, 1.0, 0.0, "x").affine(1.0, -2.0);
  EXPECT_NEAR(s.value(0.25), 1.0 - 2.0 * 2.0, kRoundOff);
  EXPECT_EQ(s.min_value(), -3.0);
}

TEST(TimeProfile, BadValuesNameTheKeyAndTheRule) {
  expect_error(
      [] {
        (void)TimeProfile::table({0.0, 1.0, 1.0}, {1, 2, 3}, "d.v");
      },
      "d.v.t_s[2]", "strictly increasing");
  expect_error(
      [] {
        (void)TimeProfile::table({0.0, 1.0}, {1.0}, "d.v");
      },
      "d.v.values", "as many entries as t_s");
  expect_error([] { (void)TimeProfile::table({}, {}, "d.v"); }, "d.v.t_s", "at least one");
  expect_error([] { (void)TimeProfile::table({0.0, NAN}, {1, 2}, "d.v"); }, "d.v.t_s[1]", "finite");
  expect_error([] { (void)TimeProfile::pwm(0.0, 0.5, 1, 0, "d.v"); }, "d.v.pwm.period_s",
               "positive");
  expect_error([] { (void)TimeProfile::pwm(1.0, 1.5, 1, 0, "d.v"); }, "d.v.pwm.duty", "[0, 1]");
  expect_error([] { (void)TimeProfile::sine(0, 1, -1.0, 0, "d.v"); }, "d.v.sine.frequency_Hz",
               ">= 0");
  expect_error([] { (void)TimeProfile::step(INFINITY, 0, 1, "d.v"); }, "d.v.step.t_s", "finite");
  expect_error([] { (void)TimeProfile::constant(NAN, "d.v"); }, "d.v", "finite");
}

}  // namespace
}  // namespace tcasim
