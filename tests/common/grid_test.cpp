#include "common/grid.hpp"

#include <gtest/gtest.h>

#include "common/error.hpp"

namespace tcasim {
namespace {

TEST(InclusiveGrid, IncludesTheEndPointDespiteDecimalRoundOff) {
  const auto g = inclusive_grid(25.0, 160.0, 5.0, "--temperatures-degC");
  ASSERT_EQ(g.size(), 28u);
  EXPECT_EQ(g.front(), 25.0);
  EXPECT_EQ(g.back(), 160.0);
  EXPECT_EQ(inclusive_grid(0.0, 0.3, 0.1, "x").size(), 4u);  // 0.1 * 3 != 0.3 exactly
  EXPECT_EQ(inclusive_grid(1.0, 1.0, 0.5, "x").size(), 1u);
}

TEST(InclusiveGrid, RejectsBadStepsNamingTheKey) {
  EXPECT_THROW((void)inclusive_grid(25.0, 160.0, 0.0, "x"), InputError);
  EXPECT_THROW((void)inclusive_grid(160.0, 25.0, 5.0, "x"), InputError);
  try {
    (void)inclusive_grid(0.0, 1e9, 1e-3, "--tensions-N");
    FAIL() << "a grid of 1e12 points must be rejected";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "--tensions-N");
    EXPECT_NE(std::string(e.what()).find("million"), std::string::npos);
  }
}

}  // namespace
}  // namespace tcasim
