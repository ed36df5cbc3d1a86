// Tests of the command-line helpers of the `tcasim` program (apps/cli_util.hpp).
#include "apps/cli_util.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/error.hpp"

namespace tcasim::app {
namespace {

template <class F>
void expect_input_error(F&& f, const std::string& key) {
  try {
    f();
    ADD_FAILURE() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_FALSE(e.rule().empty());
  }
}

/// The rule of the InputError that `f` throws ("(accepted)" when it throws none).
template <class F>
std::string rule_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.rule();
  }
  return "(accepted)";
}

TEST(CliSplitList, SplitsAtTheDelimiterAndRefusesEveryEmptyItem) {
  EXPECT_EQ(split_list("a", ',', "--x", "must be a list"), std::vector<std::string>{"a"});
  EXPECT_EQ(split_list("a,b c,d", ',', "--x", "must be a list"),
            (std::vector<std::string>{"a", "b c", "d"}));
  // CLI11 2.1's own splitting drops a trailing empty item: here each empty item is an error
  // naming the flag, the value, the list's rule and where the empty item is.
  for (const char* bad : {"", ",", "1,2,", ",1", "1,,2"}) {
    expect_input_error([&] { split_list(bad, ',', "--x", "must be a list"); }, "--x");
  }
  try {
    split_list("1,2,", ',', "--orders", "must be a list of orders");
    ADD_FAILURE() << "a trailing ',' was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.value(), "1,2,");
    EXPECT_EQ(e.rule(), "must be a list of orders: item 3 of 3 is empty (a trailing ',')");
  }
  EXPECT_EQ(rule_of([] { split_list(",1", ',', "--x", "must be a list"); }),
            "must be a list: item 1 of 2 is empty (a leading ',')");
  EXPECT_EQ(rule_of([] { split_list("1::2", ':', "--x", "must be a list"); }),
            "must be a list: item 2 of 3 is empty (a doubled ':')");
}

TEST(CliRange, ParsesOneValueOrAnInclusiveRangeAndRefusesEmptyParts) {
  EXPECT_EQ(parse_range("25", "--temperatures-degC"), std::vector<double>{25.0});
  EXPECT_EQ(parse_range("25:26:0.5", "--temperatures-degC"),
            (std::vector<double>{25.0, 25.5, 26.0}));
  for (const char* bad : {"25:", "25:150:", ":150:1", "25::1", "25:150:0.125:", "25:150", "x"}) {
    expect_input_error([&] { parse_range(bad, "--temperatures-degC"); }, "--temperatures-degC");
  }
  EXPECT_EQ(rule_of([] { parse_range("25:150:", "--temperatures-degC"); }),
            "must be a number or a range START:STOP:STEP: item 3 of 3 is empty (a trailing ':')");
}

TEST(CliVector3, ParsesThreeFiniteNumbersAndNamesTheFlagOtherwise) {
  expect_input_error([&] { parse_vector3("0.01,0", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,x", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,0,1", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,nan", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,0,", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,,0", "--target-m"); }, "--target-m");
  EXPECT_EQ(parse_vector3("0.01, 0,-2e-3", "--target-m"), Eigen::Vector3d(0.01, 0.0, -2e-3));
}

TEST(CliShard, ParsesIOfNAndNamesEachBrokenRule) {
  const Shard s = parse_shard("2/5", "--shard");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  EXPECT_EQ(parse_shard("0/1", "--shard").count, 1);
  for (const char* bad : {"", "3", "1/", "/4", "a/4", "1/4x", "-1/4", "1.5/4", "1 /4"}) {
    expect_input_error([&] { parse_shard(bad, "--shard"); }, "--shard");
  }
  const auto shard_rule = [](const std::string& text) {
    return rule_of([&] { parse_shard(text, "--shard"); });
  };
  EXPECT_NE(shard_rule("4/4").find("I < N"), std::string::npos) << shard_rule("4/4");
  EXPECT_NE(shard_rule("0/0").find("shard count N in [1,"), std::string::npos) << shard_rule("0/0");
  EXPECT_NE(shard_rule("0/2000000").find("shard count N"), std::string::npos);
}

TEST(CliActuatorIndices, MapsNamesToIndicesAndRejectsUnknownOrRepeatedNames) {
  rod::RodModel m;
  m.actuators.resize(2);
  m.actuators[0].name = "tca0";
  m.actuators[1].name = "tca1";
  expect_input_error([&] { actuator_indices(m, "tca0,nope", "--actuators"); }, "--actuators");
  expect_input_error([&] { actuator_indices(m, "tca0,tca0", "--actuators"); }, "--actuators");
  EXPECT_EQ(rule_of([&] { actuator_indices(m, "tca0,", "--actuators"); }),
            "must be comma-separated actuator names: item 2 of 2 is empty (a trailing ',')");
  EXPECT_EQ(actuator_indices(m, "tca1", "--actuators"), std::vector<int>{1});
  EXPECT_EQ(actuator_indices(m, "tca1,tca0", "--actuators"), (std::vector<int>{1, 0}));
  EXPECT_EQ(actuator_indices(m, "", "--actuators"), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace tcasim::app
