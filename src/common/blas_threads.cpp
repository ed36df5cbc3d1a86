#include "common/blas_threads.hpp"

#include <dlfcn.h>

#include <cstdlib>

namespace tcasim {

namespace {

/// limit_blas_threads() with the symbols looked up in `scope` (a dlopen handle or
/// RTLD_DEFAULT).
BlasThreads limit_in(void* scope) {
  BlasThreads out;
  // OpenBLAS's exported controls (driver/others/blas_server.c): the thread count for later
  // calls, and the shutdown it runs itself before a fork (it re-creates the pool lazily should a
  // call ever need more than one thread, which a count of 1 rules out).
  using SetThreads = void (*)(int);
  using Shutdown = int (*)();
  void* const set = dlsym(scope, "openblas_set_num_threads");
  void* const shutdown = dlsym(scope, "blas_thread_shutdown_");
  out.openblas = set != nullptr;
  if (set == nullptr || shutdown == nullptr) {
    out.reason = "no OpenBLAS thread controls in the process";
    return out;
  }
  const char* const env = std::getenv("OPENBLAS_NUM_THREADS");
  if (env != nullptr && *env != '\0') {
    out.reason = "OPENBLAS_NUM_THREADS is set";
    return out;
  }
  reinterpret_cast<SetThreads>(set)(1);
  reinterpret_cast<Shutdown>(shutdown)();
  out.stopped = true;
  return out;
}

}  // namespace

BlasThreads limit_blas_threads() { return limit_in(RTLD_DEFAULT); }

BlasThreads limit_blas_threads_of(void* library) { return limit_in(library); }

}  // namespace tcasim
