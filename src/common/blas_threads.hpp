#pragma once
/// The BLAS library's own thread pool in a tcasim program. Debian's OpenBLAS (the pthread
/// build that SuiteSparse pulls in) starts nproc - 1 server threads as soon as it is loaded,
/// before main(), and lets each spin (sched_yield in a loop) for 2^28 time-stamp ticks, about
/// 0.1 s, before it sleeps. tcasim's factorizations are small and its parallel work runs on its
/// own threads (`tcasim sweep --jobs N`), so that spinning thread only takes a core away from
/// them: in a 1000-point shooting sweep (about 0.1 s of work) it ate most of one of two cores.
/// Only the UMFPACK plugin of the beam FE (beam_fe/umfpack_plugin.cpp) brings OpenBLAS into
/// tcasim's programs, at its dlopen; its loader calls limit_blas_threads_of() right after.
#include <string>

namespace tcasim {

/// What limit_blas_threads() found and did.
struct BlasThreads {
  bool openblas = false;  ///< OpenBLAS's thread controls are linked into the process
  bool stopped = false;   ///< its thread pool was set to one thread and its server threads ended
  std::string reason;     ///< why nothing was done (empty when stopped)
};

/// Makes OpenBLAS single-threaded and ends its (idle, spinning) server threads, unless the
/// environment variable OPENBLAS_NUM_THREADS is set (then the user's choice stands). Does
/// nothing without OpenBLAS (reference BLAS, no BLAS at all). The symbols are looked up at run
/// time, so no OpenBLAS header or link is needed. Call it early in main(), before any other
/// thread exists; results do not change (OpenBLAS threads only split whole blocks of a product,
/// and the matrices tcasim factorizes are below its threading threshold anyway).
BlasThreads limit_blas_threads();

/// limit_blas_threads() for the OpenBLAS among the dependencies of `library`, a handle of
/// dlopen: a library opened with RTLD_LOCAL keeps its symbols out of the global scope that
/// limit_blas_threads() searches. Call it right after dlopen (OpenBLAS starts its threads
/// while it is loaded), before the library is used.
BlasThreads limit_blas_threads_of(void* library);

}  // namespace tcasim
