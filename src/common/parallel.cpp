#include "common/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace tcasim {

std::vector<IndexRange> fixed_chunks(std::size_t count, std::size_t chunk_size) {
  if (chunk_size == 0) throw std::invalid_argument("fixed_chunks: chunk_size must be >= 1");
  std::vector<IndexRange> chunks;
  chunks.reserve(count / chunk_size + 1);
  for (std::size_t b = 0; b < count; b += chunk_size) {
    chunks.push_back({b, std::min(count, b + chunk_size)});
  }
  return chunks;
}

IndexRange part_of(std::size_t count, std::size_t index, std::size_t parts) {
  if (index >= parts) throw std::invalid_argument("part_of: index must be < parts");
  // i count fits in 64 bits for every count and part number below 2^32.
  const auto bound = [&](std::size_t i) {
    return static_cast<std::size_t>((static_cast<unsigned long long>(i) * count) / parts);
  };
  return {bound(index), bound(index + 1)};
}

void run_parallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& task) {
  if (jobs < 1) throw std::invalid_argument("run_parallel: jobs must be >= 1");
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex error_mutex;
  std::exception_ptr first_error;
  const auto work = [&] {
    while (!stop.load()) {
      const std::size_t i = next.fetch_add(1);
      if (i >= count) return;
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        stop.store(true);
      }
    }
  };
  const std::size_t threads = std::min<std::size_t>(static_cast<std::size_t>(jobs), count);
  std::vector<std::thread> pool;
  pool.reserve(threads > 0 ? threads - 1 : 0);
  try {
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  } catch (...) {  // no thread could be started: stop the ones that were, then report
    stop.store(true);
    for (auto& t : pool) t.join();
    throw;
  }
  work();
  for (auto& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace tcasim
