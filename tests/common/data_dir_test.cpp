// Tests of the run-time lookup of the shipped data folder (common/data_dir.hpp).
#include "common/data_dir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace tcasim {
namespace {

TEST(DataDirectory, TheEnvironmentVariableComesFirstAndIsTakenAsGiven) {
  ASSERT_EQ(setenv("TCASIM_DATA_DIR", "/no/such/folder", 1), 0);
  EXPECT_EQ(data_directory(), "/no/such/folder");
  EXPECT_EQ(data_directory_candidates().front(), "/no/such/folder");
  ASSERT_EQ(unsetenv("TCASIM_DATA_DIR"), 0);
}

TEST(DataDirectory, WithoutTheVariableTheFirstFolderWithMaterialsIsChosen) {
  ASSERT_EQ(setenv("TCASIM_DATA_DIR", "", 1), 0);  // empty counts as unset
  const auto candidates = data_directory_candidates();
  // Next to this program, the configured prefix's, the build tree's.
  ASSERT_GE(candidates.size(), 2u);
  EXPECT_EQ(std::filesystem::path(candidates.back()).filename(), "data");
  const std::string chosen = data_directory();
  EXPECT_TRUE(std::filesystem::is_directory(std::filesystem::path(chosen) / "materials")) << chosen;
  for (const std::string& dir : candidates) {
    if (dir == chosen) break;
    EXPECT_FALSE(std::filesystem::is_directory(std::filesystem::path(dir) / "materials"))
        << dir << " holds materials but " << chosen << " was chosen";
  }
  ASSERT_EQ(unsetenv("TCASIM_DATA_DIR"), 0);
}

}  // namespace
}  // namespace tcasim
