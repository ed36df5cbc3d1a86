// The contact suite validation/scenarios/contact/ (validate_contact): every file is read
// by read_scenario, which runs check_obstacles (no obstacle contains the base point, none
// is penetrated by the stress-free shape), and each names its obstacles.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "rod/scenario.hpp"

namespace tcasim::rod {
namespace {

/// The scenarios validate_contact reads by name (validation/contact/validate_contact.cpp).
const std::set<std::string> kContactSuite = {"heavy-rod-floor",        "propped-cantilever-sphere",
                                             "tca-finger-cylinder",    "gripper-finger-wall",
                                             "soft-rod-floor",         "three-tca-sphere",
                                             "rectangle-plane-corner", "tapered-tentacle-box"};

TEST(ContactScenarios, EveryFileParsesWithObstacles) {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios" / "contact";
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    const std::string path = entry.path().string();
    try {
      const RodModel m = read_scenario(path);
      EXPECT_EQ(m.name + ".json", entry.path().filename().string()) << path;
      EXPECT_FALSE(m.comment.empty()) << path;
      EXPECT_FALSE(m.obstacles.empty()) << path << " has no obstacles";
      names.insert(m.name);
    } catch (const std::exception& e) {
      ADD_FAILURE() << path << ": " << e.what();
    }
  }
  EXPECT_EQ(names, kContactSuite);
}

}  // namespace
}  // namespace tcasim::rod
