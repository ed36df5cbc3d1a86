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

TEST(CliVector3, ParsesThreeFiniteNumbersAndNamesTheFlagOtherwise) {
  expect_input_error([&] { parse_vector3("0.01,0", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,x", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,0,1", "--target-m"); }, "--target-m");
  expect_input_error([&] { parse_vector3("0.01,0,nan", "--target-m"); }, "--target-m");
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
  const auto rule_of = [](const std::string& text) {
    try {
      parse_shard(text, "--shard");
    } catch (const InputError& e) {
      return e.rule();
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(rule_of("4/4").find("I < N"), std::string::npos) << rule_of("4/4");
  EXPECT_NE(rule_of("0/0").find("shard count N in [1,"), std::string::npos) << rule_of("0/0");
  EXPECT_NE(rule_of("0/2000000").find("shard count N"), std::string::npos);
}

TEST(CliActuatorIndices, MapsNamesToIndicesAndRejectsUnknownOrRepeatedNames) {
  rod::RodModel m;
  m.actuators.resize(2);
  m.actuators[0].name = "tca0";
  m.actuators[1].name = "tca1";
  expect_input_error([&] { actuator_indices(m, "tca0,nope", "--actuators"); }, "--actuators");
  expect_input_error([&] { actuator_indices(m, "tca0,tca0", "--actuators"); }, "--actuators");
  EXPECT_EQ(actuator_indices(m, "tca1", "--actuators"), std::vector<int>{1});
  EXPECT_EQ(actuator_indices(m, "tca1,tca0", "--actuators"), (std::vector<int>{1, 0}));
  EXPECT_EQ(actuator_indices(m, "", "--actuators"), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace tcasim::app
