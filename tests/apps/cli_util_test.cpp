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
