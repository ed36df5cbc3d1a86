// Atomic output (rod/output_file.hpp): a file is written whole or not at all, and a failed
// write leaves an existing file intact and no temporary behind.
#include "rod/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/error.hpp"

namespace tcasim::rod {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Entries of `dir` (to see that no temporary is left behind).
int entries(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.exists() ? 1 : 0;
  return n;
}

class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tcasim_output_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(OutputFile, WritesAndReplacesWholeFiles) {
  const fs::path f = dir_ / "result.json";
  write_file_atomically(f.string(), "first\n", "result file");
  EXPECT_EQ(read(f), "first\n");
  write_file_atomically(f.string(), "second\n", "result file");
  EXPECT_EQ(read(f), "second\n");
  EXPECT_EQ(entries(dir_), 1);
}

TEST_F(OutputFile, FailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  const fs::path f = dir_ / "sweep.csv";
  write_file_atomically(f.string(), "old content\n", "--out");
  // A file-size limit below the new text makes write(2) fail part-way (EFBIG; SIGXFSZ
  // ignored so the process survives): the situation of a full disk.
  constexpr rlim_t kLimit = 4096;
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit lowered = saved;
  lowered.rlim_cur = kLimit;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &lowered), 0);
  bool threw = false;
  std::string message;
  try {
    write_file_atomically(f.string(), std::string(4 * kLimit, 'x'), "--out");
  } catch (const InputError& e) {
    threw = true;
    message = e.what();
  }
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &saved), 0);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_TRUE(threw);
  EXPECT_NE(message.find("--out = \"" + f.string() + "\" could not be written"), std::string::npos)
      << message;
  EXPECT_EQ(read(f), "old content\n");
  EXPECT_EQ(entries(dir_), 1) << "a temporary was left behind";
}

TEST_F(OutputFile, FailedRenameLeavesNoTemporary) {
  // The destination is a non-empty folder: the rename fails after the text was written.
  const fs::path target = dir_ / "occupied";
  fs::create_directories(target / "inside");
  EXPECT_THROW(write_file_atomically(target.string(), "text", "vtk file"), InputError);
  EXPECT_EQ(entries(dir_), 1);
  EXPECT_TRUE(fs::is_directory(target / "inside"));
}

TEST_F(OutputFile, MissingFolderIsAnInputErrorNamingThePath) {
  const fs::path f = dir_ / "no-such-folder" / "out.csv";
  try {
    write_file_atomically(f.string(), "text", "--out");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "--out");
    EXPECT_NE(e.rule().find("cannot be opened for writing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tcasim::rod
