// Tests of the progress reporter (common/progress.hpp): whole lines for logs, in-place
// updates on a terminal.
#include "common/progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace tcasim {
namespace {

/// Everything written to a temporary file.
std::string contents(std::FILE* f) {
  std::rewind(f);
  std::string s;
  for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) s += static_cast<char>(c);
  return s;
}

/// Options whose time trigger never fires in a test (only the fraction trigger counts).
constexpr ProgressOptions kEveryTenthOnly{0.1, 1e9};

TEST(ProgressReporter, WritesOneWholeLinePerTenthOfTheTotalWhenNotATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressReporter progress(f, "tcasim sweep", 100, "points", kEveryTenthOnly, false);
  for (std::size_t k = 1; k <= 100; ++k) progress.update(k);
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\r'), 0);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 10);
  EXPECT_NE(out.find("tcasim sweep: 10/100 points"), std::string::npos);
  EXPECT_EQ(out.find("tcasim sweep: 11/100 points"), std::string::npos);
  EXPECT_NE(out.find("tcasim sweep: 100/100 points"), std::string::npos);
}

TEST(ProgressReporter, AlwaysWritesTheLastPointAndPrintsShortLoopsWhole) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressReporter progress(f, "sweep", 3, "points", kEveryTenthOnly, false);
  for (std::size_t k = 1; k <= 3; ++k) progress.update(k);  // a tenth of 3 is under one point
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 3);
  EXPECT_NE(out.find("sweep: 3/3 points"), std::string::npos);
}

TEST(ProgressReporter, WritesALineWhenTheIntervalHasPassedEvenBeforeATenth) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressReporter progress(f, "sweep", 1000, "points", ProgressOptions{0.1, 0.0}, false);
  progress.update(1);
  progress.update(2);
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 2);
}

TEST(ProgressReporter, RewritesOneLineInPlaceOnATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressReporter progress(f, "sweep", 20, "points", kEveryTenthOnly, true);
  for (std::size_t k = 1; k <= 20; ++k) progress.update(k);
  const std::string out = contents(f);
  std::fclose(f);
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
