#include "common/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

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

}  // namespace
}  // namespace tcasim
