#include "common/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <thread>

#if defined(__linux__) && defined(__GLIBC__)
#include <pthread.h>
#include <sched.h>
#define TCASIM_PLACE_THREADS 1
#endif

namespace tcasim {

namespace internal {

std::vector<int> start_cpus(const std::vector<int>& allowed, int current, std::size_t workers) {
  const auto here = std::find(allowed.begin(), allowed.end(), current);
  if (allowed.size() < 2 || here == allowed.end()) return {};
  const std::size_t n = allowed.size();
  const auto after = static_cast<std::size_t>(here - allowed.begin()) + 1;
  std::vector<int> cpus;
  cpus.reserve(workers);
  for (std::size_t w = 0; w < workers; ++w) cpus.push_back(allowed[(after + w) % n]);
  return cpus;
}

}  // namespace internal

namespace {

#ifdef TCASIM_PLACE_THREADS
/// The further threads of run_parallel, each started on the CPU start_cpus gives it; its
/// first act is to take the caller's whole CPU set back (a start, not a binding).
class Workers {
 public:
  explicit Workers(std::size_t count) {
    if (count == 0) return;  // the caller alone: nothing to place
    starts_.reserve(count);
    ids_.reserve(count);
    cpu_set_t caller;
    CPU_ZERO(&caller);
    if (pthread_getaffinity_np(pthread_self(), sizeof caller, &caller) != 0) return;
    std::vector<int> allowed;
    for (int c = 0; c < CPU_SETSIZE; ++c) {
      if (CPU_ISSET(c, &caller)) allowed.push_back(c);
    }
    cpus_ = internal::start_cpus(allowed, sched_getcpu(), count);
    caller_ = caller;
  }
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  ~Workers() { join(); }

  /// Starts body() on a new thread (std::system_error when no thread can be started).
  void start(const std::function<void()>& body) {
    starts_.push_back(std::make_unique<Start>(Start{&body, nullptr}));
    Start* s = starts_.back().get();
    pthread_t id{};
    int rc = -1;
    if (ids_.size() < cpus_.size()) {  // on its start CPU
      s->widen_to = &caller_;
      rc = create_on(cpus_[ids_.size()], s, id);
    }
    if (rc != 0) {  // no start CPU, or it was refused: where Linux puts it
      s->widen_to = nullptr;
      rc = pthread_create(&id, nullptr, &run, s);
    }
    if (rc != 0) {
      starts_.pop_back();
      throw std::system_error(rc, std::generic_category(), "run_parallel: cannot start a thread");
    }
    ids_.push_back(id);
  }

  void join() {
    for (pthread_t id : ids_) pthread_join(id, nullptr);
    ids_.clear();
  }

 private:
  struct Start {
    const std::function<void()>* body;
    const cpu_set_t* widen_to;  ///< started on one CPU: the set to take back first
  };
  static int create_on(int cpu, Start* s, pthread_t& id) {
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0) return -1;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    int rc = pthread_attr_setaffinity_np(&attr, sizeof one, &one);
    if (rc == 0) rc = pthread_create(&id, &attr, &run, s);
    pthread_attr_destroy(&attr);
    return rc;
  }
  static void* run(void* arg) {
    const Start& s = *static_cast<const Start*>(arg);
    if (s.widen_to != nullptr) {
      (void)pthread_setaffinity_np(pthread_self(), sizeof *s.widen_to, s.widen_to);
    }
    (*s.body)();
    return nullptr;
  }

  std::vector<int> cpus_;
  cpu_set_t caller_{};
  std::vector<std::unique_ptr<Start>> starts_;
  std::vector<pthread_t> ids_;
};
#else
/// The further threads of run_parallel, where the system puts them.
class Workers {
 public:
  explicit Workers(std::size_t count) { threads_.reserve(count); }
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  ~Workers() { join(); }
  void start(const std::function<void()>& body) { threads_.emplace_back(body); }
  void join() {
    for (auto& t : threads_) t.join();
    threads_.clear();
  }

 private:
  std::vector<std::thread> threads_;
};
#endif

}  // namespace

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
  const std::function<void()> work = [&] {
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
  Workers pool(threads > 0 ? threads - 1 : 0);
  try {
    for (std::size_t t = 1; t < threads; ++t) pool.start(work);
  } catch (...) {  // no thread could be started: stop the ones that were, then report
    stop.store(true);
    pool.join();
    throw;
  }
  work();
  pool.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace tcasim
