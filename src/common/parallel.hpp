#pragma once
/// Contiguous index ranges and a small thread pool for independent tasks (the chunks of a
/// parallel sweep, `tcasim sweep --jobs N`). No global state.
#include <cstddef>
#include <functional>
#include <vector>

namespace tcasim {

/// The indices [begin, end).
struct IndexRange {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
  bool operator==(const IndexRange& o) const { return begin == o.begin && end == o.end; }
};

/// [0, count) cut into consecutive ranges of `chunk_size` indices (the last one shorter);
/// empty for count = 0. chunk_size must be >= 1 (std::invalid_argument otherwise).
std::vector<IndexRange> fixed_chunks(std::size_t count, std::size_t chunk_size);

/// Part `index` (0-based) of `parts` contiguous parts of [0, count):
/// [floor(index count / parts), floor((index + 1) count / parts)). The parts cover [0, count)
/// in order without overlap and differ in size by at most one; a part is empty when
/// parts > count. Needs index < parts (std::invalid_argument otherwise).
IndexRange part_of(std::size_t count, std::size_t index, std::size_t parts);

/// Runs task(i) once for every i in [0, count) on min(jobs, count) threads (the calling
/// thread is one of them), handing the indices out in increasing order as threads become
/// free. After a task throws, no further index is handed out; once every thread has
/// stopped, the first exception is rethrown. jobs must be >= 1 (std::invalid_argument).
///
/// On Linux each further thread starts on a CPU of its own (start_cpus) and then takes the
/// caller's whole CPU set, so the scheduler stays free to move it. Linux starts a new thread
/// on its creator's CPU and moves it to an idle CPU only when it balances the load, which on
/// a 2-core virtual machine took 3 to 12 ms while the two threads shared one CPU: 12 % of the
/// time of a 1000-point sweep on 2 threads (docs/benchmarks.md).
void run_parallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& task);

namespace internal {
/// The CPUs the `workers` further threads of run_parallel start on (one each, in order):
/// `allowed` (the caller's CPU set, in increasing order) taken cyclically from the CPU after
/// `current` (the caller's CPU), which comes last, so the first workers get CPUs of their
/// own. Empty when fewer than two CPUs are allowed (nothing to spread over) or when
/// `current` is not among them.
std::vector<int> start_cpus(const std::vector<int>& allowed, int current, std::size_t workers);
}  // namespace internal

}  // namespace tcasim
