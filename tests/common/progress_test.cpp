// Tests of the progress reporter (common/progress.hpp): whole lines for logs, in-place
// updates on a terminal.
#include "common/progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace tcasim {
namespace {

/// What a reporter writes for updates 1..total (into a temporary file).
std::string report(std::size_t total, ProgressOptions options, bool interactive) {
  std::FILE* f = std::tmpfile();
  if (f == nullptr) return "(no temporary file)";
  {
    ProgressReporter progress(f, "sweep", total, "points", options, interactive);
    for (std::size_t k = 1; k <= total; ++k) progress.update(k);
  }
  std::rewind(f);
  std::string s;
  for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) s += static_cast<char>(c);
  std::fclose(f);
  return s;
}

/// Options whose time trigger never fires in a test (only the fraction trigger counts).
constexpr ProgressOptions kEveryTenthOnly{0.1, 1e9};

TEST(ProgressReporter, WritesOneWholeLinePerTenthOfTheTotalWhenNotATerminal) {
  const std::string out = report(100, kEveryTenthOnly, false);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\r'), 0);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 10);
  EXPECT_NE(out.find("sweep: 10/100 points"), std::string::npos);
  EXPECT_EQ(out.find("sweep: 11/100 points"), std::string::npos);
  EXPECT_NE(out.find("sweep: 100/100 points"), std::string::npos);
}

TEST(ProgressReporter, AlwaysWritesTheLastPointAndPrintsShortLoopsWhole) {
  const std::string out = report(3, kEveryTenthOnly, false);  // a tenth of 3 is under one point
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 3);
  EXPECT_NE(out.find("sweep: 3/3 points"), std::string::npos);
}

TEST(ProgressReporter, WritesALineWheneverTheIntervalHasPassed) {
  const std::string out =
      report(1000, ProgressOptions{0.1, 0.0}, false);  // interval 0: every update
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1000);
}

TEST(ProgressReporter, RewritesOneLineInPlaceOnATerminal) {
  const std::string out = report(20, kEveryTenthOnly, true);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\r'), 20);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1);
  EXPECT_EQ(out.back(), '\n');
}

TEST(ProgressReporter, AFileIsNotATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  EXPECT_FALSE(ProgressReporter(f, "sweep", 10).interactive());
  std::fclose(f);
}

}  // namespace
}  // namespace tcasim
