#include "common/blas_threads.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdlib>
#include <filesystem>

// The Fortran BLAS product C = alpha A B + beta C (column-major), from the BLAS this test links
// (the one SuiteSparse uses).
extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc);

namespace tcasim {
namespace {

std::size_t threads_of_this_process() {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry :
       std::filesystem::directory_iterator("/proc/self/task")) {
    ++n;
  }
  return n;
}

// A product large enough (256^3 multiply-adds) that a multi-threaded OpenBLAS would split it.
constexpr int kProductSize = 256;
// Round-off of a 256-term dot product of numbers in [-1, 1], with room for a different
// summation order than Eigen's.
constexpr double kProductTolerance = 1e-12;

TEST(LimitBlasThreads, EndsOpenBlasServerThreadsAndBlasStillComputes) {
  const char* env = std::getenv("OPENBLAS_NUM_THREADS");
  if (env != nullptr && *env != '\0') GTEST_SKIP() << "OPENBLAS_NUM_THREADS is set";
  const std::size_t before = threads_of_this_process();
  const BlasThreads r = limit_blas_threads();
  if (!r.openblas) GTEST_SKIP() << "the linked BLAS is not OpenBLAS: " << r.reason;
  EXPECT_TRUE(r.stopped) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  // OpenBLAS started nproc - 1 server threads at load time; none is left.
  EXPECT_EQ(threads_of_this_process(), 1u) << before << " thread(s) before";

  // BLAS works single-threaded afterwards and starts no thread again.
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(kProductSize, kProductSize);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(kProductSize, kProductSize);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(kProductSize, kProductSize);
  const double one = 1.0, zero = 0.0;
  const int n = kProductSize;
  dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n);
  EXPECT_LE((c - a * b).cwiseAbs().maxCoeff(), kProductTolerance);
  EXPECT_EQ(threads_of_this_process(), 1u);

  // A second call is harmless (the pool is already gone).
  EXPECT_TRUE(limit_blas_threads().stopped);
  EXPECT_EQ(threads_of_this_process(), 1u);
}

}  // namespace
}  // namespace tcasim
