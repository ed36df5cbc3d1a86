// Tests of the command-line helpers of the `tcasim` program (apps/cli_util.hpp).
#include "apps/cli_util.hpp"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/error.hpp"
#include "support/input_error.hpp"

namespace tcasim::app {
namespace {

using test_support::expect_input_error;
using test_support::input_error_rule;

// The shared expectation (tests/support/input_error.hpp) fails on every wrong outcome.
TEST(TestSupportInputError, FailsWithoutAnErrorOrOnAnotherKeyOrRule) {
  EXPECT_NONFATAL_FAILURE(expect_input_error([] {}, "k"), "no InputError for k");
  EXPECT_NONFATAL_FAILURE(expect_input_error([] { throw InputError("a", "1", "r"); }, "b"), "b");
  EXPECT_NONFATAL_FAILURE(
      expect_input_error([] { throw InputError("a", "1", "must be > 0"); }, "a", "integer"),
      "rule without 'integer'");
  expect_input_error([] { throw InputError("a", "1", "must be > 0"); }, "a", "> 0");
  EXPECT_EQ(input_error_rule([] {}), "(accepted)");
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
  EXPECT_EQ(input_error_rule([] { split_list(",1", ',', "--x", "must be a list"); }),
            "must be a list: item 1 of 2 is empty (a leading ',')");
  EXPECT_EQ(input_error_rule([] { split_list("1::2", ':', "--x", "must be a list"); }),
            "must be a list: item 2 of 3 is empty (a doubled ':')");
}

TEST(CliRange, ParsesOneValueOrAnInclusiveRangeAndRefusesEmptyParts) {
  EXPECT_EQ(parse_range("25", "--temperatures-degC"), std::vector<double>{25.0});
  EXPECT_EQ(parse_range("25:26:0.5", "--temperatures-degC"),
            (std::vector<double>{25.0, 25.5, 26.0}));
  for (const char* bad : {"25:", "25:150:", ":150:1", "25::1", "25:150:0.125:", "25:150", "x"}) {
    expect_input_error([&] { parse_range(bad, "--temperatures-degC"); }, "--temperatures-degC");
  }
  EXPECT_EQ(input_error_rule([] { parse_range("25:150:", "--temperatures-degC"); }),
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
    return input_error_rule([&] { parse_shard(text, "--shard"); });
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
  EXPECT_EQ(input_error_rule([&] { actuator_indices(m, "tca0,", "--actuators"); }),
            "must be comma-separated actuator names: item 2 of 2 is empty (a trailing ',')");
  EXPECT_EQ(actuator_indices(m, "tca1", "--actuators"), std::vector<int>{1});
  EXPECT_EQ(actuator_indices(m, "tca1,tca0", "--actuators"), (std::vector<int>{1, 0}));
  EXPECT_EQ(actuator_indices(m, "", "--actuators"), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace tcasim::app
