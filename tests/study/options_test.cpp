// Tests of the options layer (study/options.hpp) that the command line and the Python module
// both check their options with: a given value is never taken for "not given", and a refusal
// has the same value and rule in both front ends, only the option's name differs.
#include "study/options.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/error.hpp"
#include "study/simulation.hpp"

namespace tcasim::study {
namespace {

/// The InputError `f` throws (fails the test when it throws none).
InputError refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

/// Checks that `check` refuses in both styles with the same value and rule, under the key's
/// flag and keyword names; returns the Python-style error.
InputError same_refusal_in_both_styles(const std::string& key,
                                       const std::function<void(OptionNames)>& check) {
  const InputError python = refusal([&] { check(OptionNames::kPython); });
  const InputError flags = refusal([&] { check(OptionNames::kFlags); });
  EXPECT_EQ(python.key(), key);
  EXPECT_EQ(flags.key(), option_name(key, OptionNames::kFlags));
  EXPECT_EQ(python.value(), flags.value());
  EXPECT_EQ(python.rule(), flags.rule());
  return python;
}

TEST(Options, NamesReadAsKeywordsOrFlags) {
  EXPECT_EQ(option_name("linear_solver", OptionNames::kPython), "linear_solver");
  EXPECT_EQ(option_name("linear_solver", OptionNames::kFlags), "--linear-solver");
  EXPECT_EQ(option_name("viscosity_Pa_s", OptionNames::kFlags), "--viscosity-Pa-s");
}

TEST(Options, AbsentShootingOptionsGiveTheSolverDefaults) {
  const cosserat::Options o = shooting_options({}, OptionNames::kFlags);
  const cosserat::Options defaults;
  EXPECT_EQ(o.integrator.method, ode::Method::kRk4);
  EXPECT_EQ(o.integrator.steps, defaults.integrator.steps);
  EXPECT_TRUE(o.planar_reduction);
}

TEST(Options, ZeroStepsAndZeroRtolAreRefusedNotTheDefaults) {
  ShootingChoice steps;
  steps.steps = 0;
  const InputError e =
      same_refusal_in_both_styles("steps", [&](OptionNames s) { shooting_options(steps, s); });
  EXPECT_EQ(e.value(), "0");
  EXPECT_EQ(e.rule(), "must be an even number in [2, 100000]");
  ShootingChoice rtol;
  rtol.rtol = 0.0;
  const InputError r =
      same_refusal_in_both_styles("rtol", [&](OptionNames s) { shooting_options(rtol, s); });
  EXPECT_EQ(r.rule(), "must be in (0, 1)");
}

TEST(Options, CountsBeyondTheIntRangeAreReportedExactly) {
  ShootingChoice c;
  c.steps = 1000000000001;  // beyond int: must not wrap or round
  const InputError e =
      same_refusal_in_both_styles("steps", [&](OptionNames s) { shooting_options(c, s); });
  EXPECT_EQ(e.value(), "1000000000001");
  FeChoice fe;
  fe.elements = 9007199254740993;  // 2^53 + 1: a double would print ...992
  EXPECT_EQ(
      same_refusal_in_both_styles("elements", [&](OptionNames s) { fe_options(fe, s); }).value(),
      "9007199254740993");
}

TEST(Options, RtolExcludesStepsAndSchemeByName) {
  ShootingChoice c;
  c.rtol = 1e-6;
  c.steps = 10;
  const InputError flags = refusal([&] { shooting_options(c, OptionNames::kFlags); });
  EXPECT_EQ(flags.key(), "--rtol");
  EXPECT_EQ(flags.rule(), "excludes --steps and --scheme (CVODE chooses its own steps)");
}

TEST(Options, GivenValuesReachTheSolverOptions) {
  ShootingChoice c;
  c.steps = 40;
  c.scheme = "rk8";
  c.no_planar = true;
  const cosserat::Options o = shooting_options(c, OptionNames::kPython);
  EXPECT_EQ(o.integrator.steps, 40);
  EXPECT_EQ(o.integrator.method, ode::Method::kRk8);
  EXPECT_EQ(o.coarse_steps, 2);
  EXPECT_FALSE(o.planar_reduction);
  FeChoice fe;
  fe.elements = 8;
  fe.order = 1;
  fe.integration = "full";
  const beam_fe::Options f = fe_options(fe, OptionNames::kPython);
  EXPECT_EQ(f.elements, 8);
  EXPECT_EQ(f.order, 1);
  EXPECT_EQ(f.integration, beam_fe::Integration::kFull);
}

TEST(Options, FeAndSweepOptionsRefuseByRule) {
  FeChoice order;
  order.order = 3;
  EXPECT_EQ(
      same_refusal_in_both_styles("order", [&](OptionNames s) { fe_options(order, s); }).rule(),
      "must be 1 or 2");
  FeChoice rule;
  rule.integration = "exact";
  same_refusal_in_both_styles("integration", [&](OptionNames s) { fe_options(rule, s); });
  same_refusal_in_both_styles("jobs", [](OptionNames s) { check_sweep_jobs(0, 1, s); });
  same_refusal_in_both_styles("chunk", [](OptionNames s) { check_sweep_jobs(1, 0, s); });
  same_refusal_in_both_styles("method", [](OptionNames s) { check_method("bem", s); });
}

TEST(Options, SimulationStepsZeroIsRefusedAndAbsentIsTheRecommendation) {
  SimulationOptions o;
  o.duration_s = 0.002;
  o.dt_s = 0.001;
  EXPECT_EQ(check_simulation_options(o, OptionNames::kFlags), 2);
  o.steps = 0;
  EXPECT_EQ(
      same_refusal_in_both_styles("steps", [&](OptionNames s) { check_simulation_options(o, s); })
          .rule(),
      "must be an integer in [1, 100000]");
  o.steps.reset();
  o.rho_inf = 1.5;
  same_refusal_in_both_styles("rho_inf", [&](OptionNames s) { check_simulation_options(o, s); });
}

}  // namespace
}  // namespace tcasim::study
