// Tests of the gate rules of the validation programs (validation/common/gates.hpp): a gate
// set cannot pass empty, with a non-finite measurement, short of its declared cases, or
// with a case that was not run.
#include "validation/common/gates.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace tcasim::validation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Gates, AnEmptyGateSetFails) {
  const Gates gates("empty");
  EXPECT_EQ(gates.finish(), 1);
}

TEST(Gates, PassingGatesGiveExitCodeZeroAndOneFailureGivesOne) {
  Gates gates("program");
  EXPECT_TRUE(gates.at_most("small", 1.0, 2.0));
  EXPECT_TRUE(gates.within("inside", 1.5, 1.0, 2.0));
  EXPECT_TRUE(gates.check("flag", true, "0 failed", "0"));
  EXPECT_EQ(gates.finish(), 0);
  EXPECT_FALSE(gates.at_most("large", 3.0, 2.0));
  EXPECT_EQ(gates.failures(), 1);
  EXPECT_EQ(gates.finish(), 1);
}

TEST(Gates, ANonFiniteMeasurementFailsEveryNumericGate) {
  Gates gates("program");
  for (double v : {kNaN, kInf, -kInf}) {
    EXPECT_FALSE(gates.at_most("at_most", v, 1.0));
    EXPECT_FALSE(gates.within("within", v, -1e300, 1e300));
  }
  EXPECT_EQ(gates.failures(), static_cast<int>(gates.records().size()));
}

TEST(Gates, ANonFiniteBoundFailsInsteadOfMakingAGateThatCannotFail) {
  Gates gates("program");
  EXPECT_FALSE(gates.at_most("bound inf", 1.0, kInf));
  EXPECT_FALSE(gates.at_most("bound nan", 1.0, kNaN));
  EXPECT_FALSE(gates.within("open bracket", 1.0, -kInf, kInf));
  EXPECT_FALSE(gates.within("nan bracket", 1.0, kNaN, 2.0));
}

TEST(Gates, ACheckWhoseMeasuredTextNamesANonFiniteNumberFails) {
  Gates gates("program");
  EXPECT_FALSE(gates.check("nan", true, "nan", "< 1"));
  EXPECT_FALSE(gates.check("signed nan", true, "-nan m", "< 1"));
  EXPECT_FALSE(gates.check("inf in a sentence", true, "radius inf m at 25 degC", "finite"));
  EXPECT_FALSE(gates.check("upper case", true, "NaN", "< 1"));
  EXPECT_FALSE(gates.check("infinity", true, "-Infinity", "< 1"));
  EXPECT_TRUE(
      gates.check("words containing inf or nan", true, "information: finance, nano 1.0e-3", "ok"));
  EXPECT_EQ(gates.failures(), 5);
}

TEST(Gates, FewerCasesThanDeclaredFail) {
  Gates gates("program");
  EXPECT_TRUE(gates.expect_count("scenarios", 14, 14));
  EXPECT_TRUE(gates.expect_count("scenarios, more than declared", 15, 14));
  EXPECT_FALSE(gates.expect_count("scenarios, one lost", 13, 14));
  EXPECT_FALSE(gates.expect_count("points, none declared", 0, 0));
  EXPECT_EQ(gates.failures(), 2);
}

TEST(Gates, ACaseNotRunFailsTheProgram) {
  Gates gates("program");
  EXPECT_TRUE(gates.at_most("ran", 0.5, 1.0));
  gates.not_run("helical-string", "the FE does not support helical routing");
  ASSERT_EQ(gates.records().size(), 2u);
  EXPECT_FALSE(gates.records().back().passed);
  EXPECT_EQ(gates.records().back().name, "helical-string: not run");
  EXPECT_EQ(gates.finish(), 1);
}

}  // namespace
}  // namespace tcasim::validation
