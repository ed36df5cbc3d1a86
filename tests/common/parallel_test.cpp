#include "common/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#if defined(__linux__) && defined(__GLIBC__)
#include <pthread.h>
#include <sched.h>
#endif

namespace tcasim {
namespace {

TEST(FixedChunks, CutsConsecutiveRangesWithAShorterLastOne) {
  const auto c = fixed_chunks(10, 4);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], (IndexRange{0, 4}));
  EXPECT_EQ(c[1], (IndexRange{4, 8}));
  EXPECT_EQ(c[2], (IndexRange{8, 10}));
  EXPECT_EQ(fixed_chunks(8, 4).size(), 2u);
  EXPECT_TRUE(fixed_chunks(0, 4).empty());
  EXPECT_EQ(fixed_chunks(3, 100).size(), 1u);
  EXPECT_THROW((void)fixed_chunks(3, 0), std::invalid_argument);
}

TEST(PartOf, PartsCoverTheRangeInOrderAndDifferByAtMostOne) {
  for (std::size_t count : {0u, 1u, 5u, 7u, 100u}) {
    for (std::size_t parts : {1u, 2u, 3u, 8u}) {
      std::size_t expected_begin = 0, smallest = count, largest = 0;
      for (std::size_t i = 0; i < parts; ++i) {
        const IndexRange r = part_of(count, i, parts);
        EXPECT_EQ(r.begin, expected_begin) << count << " " << i << "/" << parts;
        EXPECT_LE(r.begin, r.end);
        expected_begin = r.end;
        smallest = std::min(smallest, r.size());
        largest = std::max(largest, r.size());
      }
      EXPECT_EQ(expected_begin, count);
      EXPECT_LE(largest - smallest, 1u);
    }
  }
  EXPECT_THROW((void)part_of(10, 2, 2), std::invalid_argument);
}

TEST(RunParallel, RunsEveryIndexOnceOnSeveralThreads) {
  std::vector<std::atomic<int>> runs(200);
  std::mutex m;
  std::set<std::thread::id> threads;
  run_parallel(runs.size(), 3, [&](std::size_t i) {
    runs[i].fetch_add(1);
    const std::lock_guard<std::mutex> lock(m);
    threads.insert(std::this_thread::get_id());
  });
  for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
  EXPECT_GE(threads.size(), 1u);
  EXPECT_LE(threads.size(), 3u);
  // One job: everything on the calling thread, in order.
  std::vector<std::size_t> order;
  const std::thread::id caller = std::this_thread::get_id();
  run_parallel(5, 1, [&](std::size_t i) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    order.push_back(i);
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  run_parallel(0, 4, [](std::size_t) { FAIL() << "no index to run"; });
  EXPECT_THROW(run_parallel(3, 0, [](std::size_t) {}), std::invalid_argument);
}

TEST(RunParallel, RethrowsTheFirstErrorAndStopsHandingOutIndices) {
  // One thread: no index after the failing one is handed out.
  std::atomic<int> ran{0};
  EXPECT_THROW(run_parallel(1000, 1,
                            [&](std::size_t i) {
                              ran.fetch_add(1);
                              if (i == 3) throw std::runtime_error("point 3");
                            }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 4);
  // Two threads: the error reaches the caller. (How many indices the other thread takes
  // before it sees the stop depends on scheduling: with tasks this short it may take all.)
  EXPECT_THROW(run_parallel(1000, 2,
                            [&](std::size_t i) {
                              if (i == 3) throw std::runtime_error("point 3");
                            }),
               std::runtime_error);
}

TEST(StartCpus, GivesTheFirstWorkersCpusOtherThanTheCallersOne) {
  using internal::start_cpus;
  // Two CPUs, the caller on either: the worker starts on the other one.
  EXPECT_EQ(start_cpus({0, 1}, 0, 1), (std::vector<int>{1}));
  EXPECT_EQ(start_cpus({0, 1}, 1, 1), (std::vector<int>{0}));
  // More workers than free CPUs: cyclic, the caller's CPU last in every round.
  EXPECT_EQ(start_cpus({0, 1}, 0, 3), (std::vector<int>{1, 0, 1}));
  EXPECT_EQ(start_cpus({2, 5, 7, 9}, 5, 5), (std::vector<int>{7, 9, 2, 5, 7}));
  EXPECT_EQ(start_cpus({2, 5, 7, 9}, 9, 2), (std::vector<int>{2, 5}));
  // Nothing to spread over, or a caller outside its own set (sched_getcpu failed: -1).
  EXPECT_TRUE(start_cpus({3}, 3, 2).empty());
  EXPECT_TRUE(start_cpus({}, 0, 2).empty());
  EXPECT_TRUE(start_cpus({0, 1}, -1, 2).empty());
  EXPECT_TRUE(start_cpus({0, 1}, 0, 0).empty());
}

#if defined(__linux__) && defined(__GLIBC__)
std::set<int> cpu_set_of_this_thread() {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(pthread_getaffinity_np(pthread_self(), sizeof set, &set), 0);
  std::set<int> cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (CPU_ISSET(c, &set)) cpus.insert(c);
  }
  return cpus;
}

// The workers start on a CPU of their own, but only start there: each runs its tasks with the
// caller's whole CPU set, whatever that set is.
void expect_workers_run_with_the_callers_cpu_set() {
  const std::set<int> caller = cpu_set_of_this_thread();
  std::mutex m;
  std::vector<std::set<int>> seen;
  run_parallel(64, 4, [&](std::size_t) {
    const std::set<int> mine = cpu_set_of_this_thread();
    const std::lock_guard<std::mutex> lock(m);
    seen.push_back(mine);
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // let every thread take some
  });
  ASSERT_EQ(seen.size(), 64u);
  for (const auto& s : seen) EXPECT_EQ(s, caller);
}

TEST(RunParallel, WorkersRunWithTheCallersCpuSet) {
  expect_workers_run_with_the_callers_cpu_set();
  // A caller restricted to all its CPUs but the last (one of two, on a 2-core machine): so
  // are its workers.
  const std::set<int> all = cpu_set_of_this_thread();
  ASSERT_FALSE(all.empty());
  if (all.size() < 2) GTEST_SKIP() << "one CPU: no smaller set to restrict the caller to";
  std::thread restricted([&] {
    cpu_set_t fewer;
    CPU_ZERO(&fewer);
    for (int c : all) {
      if (c != *all.rbegin()) CPU_SET(c, &fewer);
    }
    ASSERT_EQ(pthread_setaffinity_np(pthread_self(), sizeof fewer, &fewer), 0);
    expect_workers_run_with_the_callers_cpu_set();
  });
  restricted.join();
}
#endif

}  // namespace
}  // namespace tcasim
