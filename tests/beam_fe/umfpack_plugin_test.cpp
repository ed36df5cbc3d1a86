// The UMFPACK back end as a plugin (beam_fe/internal/umfpack_plugin_abi.hpp): a plugin that
// cannot be loaded is an InputError naming linear_solver, umfpack, the path tried and why; the
// solver never crashes on it; once loaded, OpenBLAS's server threads (started by its dlopen) are
// gone. Its own program: one process sees the plugin's whole history (not loaded, then loaded).
#include <gtest/gtest.h>
#include <stdlib.h>  // setenv, unsetenv

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "beam_fe/beam_fe.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "models.hpp"

#ifndef TCASIM_UMFPACK_PLUGIN_FILE
#error "the test needs the plugin's file name (tests/beam_fe/CMakeLists.txt)"
#endif

namespace tcasim::beam_fe {
namespace {

namespace fs = std::filesystem;

std::size_t threads_of_this_process() {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator("/proc/self/task")) ++n;
  return n;
}

/// An empty folder, removed at the end of the scope.
struct TempFolder {
  fs::path path;
  explicit TempFolder(const std::string& name)
      : path(fs::temp_directory_path() / (name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
};

/// The InputError of parse_linear_solver("umfpack") (fails the test when it does not throw).
InputError umfpack_error() {
  try {
    parse_linear_solver("umfpack");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "parse_linear_solver(\"umfpack\") loaded a plugin";
  return InputError("", "", "");
}

TEST(UmfpackPlugin, CandidatesAreTheEnvironmentFolderAloneWhenItIsSet) {
  ASSERT_EQ(setenv("TCASIM_PLUGIN_DIR", "/nonexistent/plugins", 1), 0);
  EXPECT_EQ(umfpack_plugin_candidates(), std::vector<std::string>{"/nonexistent/plugins"});
  ASSERT_EQ(unsetenv("TCASIM_PLUGIN_DIR"), 0);
  const std::vector<std::string> all = umfpack_plugin_candidates();
  EXPECT_GE(all.size(), 2u);  // next to this program (two layouts), the prefix, the build tree
  for (const std::string& dir : all) EXPECT_EQ(fs::path(dir).filename(), "tcasim") << dir;
}

TEST(UmfpackPlugin, MissingThenBrokenThenFoundPluginAndOpenBlasThreadsEnded) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  // 1. An empty folder: the error names the key, the value, the path tried and the variable.
  const TempFolder empty("tcasim-no-plugin");
  ASSERT_EQ(setenv("TCASIM_PLUGIN_DIR", empty.path.c_str(), 1), 0);
  const std::string path = (empty.path / TCASIM_UMFPACK_PLUGIN_FILE).string();
  const InputError missing = umfpack_error();
  EXPECT_EQ(missing.key(), "linear_solver");
  EXPECT_EQ(missing.value(), "umfpack");
  EXPECT_NE(missing.rule().find("needs the UMFPACK plugin"), std::string::npos) << missing.what();
  EXPECT_NE(missing.rule().find(path + ": cannot open shared object file"), std::string::npos)
      << missing.what();
  EXPECT_NE(missing.rule().find("TCASIM_PLUGIN_DIR"), std::string::npos) << missing.what();
  // The solver, given the enum directly, reports the same error instead of solving or crashing.
  Options opt = testing::options(8, 2);
  opt.linear_solver = LinearSolver::kUmfpack;
  State st;
  EXPECT_THROW(solve(m, opt, st), InputError);

  // 2. A file of that name that is no shared library: refused with its path, no crash.
  const TempFolder broken("tcasim-broken-plugin");
  std::ofstream(broken.path / TCASIM_UMFPACK_PLUGIN_FILE) << "not a shared library\n";
  ASSERT_EQ(setenv("TCASIM_PLUGIN_DIR", broken.path.c_str(), 1), 0);
  const InputError bad = umfpack_error();
  EXPECT_NE(bad.rule().find((broken.path / TCASIM_UMFPACK_PLUGIN_FILE).string()), std::string::npos)
      << bad.what();

  // 3. The default search (a failure is not remembered) finds the build tree's plugin; the
  //    OpenBLAS it brings has no server thread left, and UMFPACK solves as KLU does.
  ASSERT_EQ(unsetenv("TCASIM_PLUGIN_DIR"), 0);
  const char* blas_env = std::getenv("OPENBLAS_NUM_THREADS");
  const bool check_threads = blas_env == nullptr || *blas_env == '\0';
  ASSERT_EQ(threads_of_this_process(), 1u);
  EXPECT_EQ(parse_linear_solver("umfpack"), LinearSolver::kUmfpack);
  if (check_threads) {
    EXPECT_EQ(threads_of_this_process(), 1u);
  }
  State su, sk;
  const Summary umf = solve(m, opt, su);
  opt.linear_solver = LinearSolver::kKlu;
  const Summary klu = solve(m, opt, sk);
  ASSERT_TRUE(umf.converged()) << umf.message;
  ASSERT_TRUE(klu.converged()) << klu.message;
  // Both converged to tolerance_rel 1e-10 of the load scale: tips agree to ~1e-12 of L.
  EXPECT_LT((su.p_W_m.back() - sk.p_W_m.back()).norm(), 1e-10 * m.length_m);
  if (check_threads) {
    EXPECT_EQ(threads_of_this_process(), 1u);
  }
}

}  // namespace
}  // namespace tcasim::beam_fe
