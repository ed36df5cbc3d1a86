#include "common/blas_threads.hpp"

#include <dlfcn.h>

#include <cstdlib>

namespace tcasim {

BlasThreads limit_blas_threads() {
  BlasThreads out;
  // OpenBLAS's exported controls (driver/others/blas_server.c): the thread count for later
  // calls, and the shutdown it runs itself before a fork (it re-creates the pool lazily should a
  // call ever need more than one thread, which a count of 1 rules out).
  using SetThreads = void (*)(int);
  using Shutdown = int (*)();
  void* const set = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  void* const shutdown = dlsym(RTLD_DEFAULT, "blas_thread_shutdown_");
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

}  // namespace tcasim
