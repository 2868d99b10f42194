// base::parallel_for: every item once, results independent of the number of threads, the lowest
// failing item's exception whatever the threads' timing.
#include "swath/base/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace swath::base {
namespace {

TEST(ParallelFor, EveryItemOnceTheSameResultsOnAnyNumberOfThreads) {
  for (const std::size_t count : {0u, 1u, 2u, 7u, 100u, 1000u}) {
    std::vector<std::uint64_t> single(count);
    parallel_for(count, 1, [&](std::size_t i) { single[i] = i * 2654435761u % 1000003; });
    for (const unsigned threads : {0u, 2u, 3u, 8u, 64u}) {
      std::vector<std::atomic<int>> calls(count);
      std::vector<std::uint64_t> slots(count, 0);
      parallel_for(count, threads, [&](std::size_t i) {
        ++calls[i];
        slots[i] = i * 2654435761u % 1000003;
      });
      for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(calls[i].load(), 1) << count << " " << i;
      EXPECT_EQ(slots, single) << count << " items on " << threads << " threads";
    }
  }
}

TEST(ParallelFor, RethrowsTheLowestFailingItemsException) {
  for (const unsigned threads : {1u, 2u, 4u, 16u})
    for (int repeat = 0; repeat < 20; ++repeat) {
      std::atomic<int> done{0};
      try {
        parallel_for(200, threads, [&](std::size_t i) {
          if (i == 150 || i == 37 || i == 90) throw std::runtime_error(std::to_string(i));
          ++done;
        });
        FAIL() << "no exception on " << threads << " threads";
      } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "37") << threads;
      }
      // Every item below the first failure ran, whatever the timing.
      EXPECT_GE(done.load(), 37) << threads;
    }
}

TEST(ParallelFor, UsesTheCallersThreadAndNoMoreThreadsThanItems) {
  std::atomic<int> calls{0};
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id ran_on;
  parallel_for(1, 8, [&](std::size_t) {
    ++calls;
    ran_on = std::this_thread::get_id();
  });
  EXPECT_EQ(calls.load(), 1);
  EXPECT_EQ(ran_on, caller);  // one item: no thread started for it
  EXPECT_GE(machine_threads(), 1u);
}

TEST(ParallelFor, EachWorkerIndexIsOneThreadTheCallersZero) {
  for (const unsigned threads : {1u, 2u, 3u, 8u})
    for (const std::size_t count : {1u, 2u, 5u, 300u}) {
      const std::thread::id caller = std::this_thread::get_id();
      std::vector<std::thread::id> of_worker(threads);
      std::vector<unsigned> worker_of(count, threads);
      std::mutex lock;
      bool consistent = true;
      parallel_for(count, threads, [&](std::size_t i, unsigned worker) {
        ASSERT_LT(worker, threads);
        worker_of[i] = worker;
        const std::lock_guard<std::mutex> guard(lock);
        if (of_worker[worker] == std::thread::id{}) of_worker[worker] = std::this_thread::get_id();
        consistent &= of_worker[worker] == std::this_thread::get_id();
      });
      EXPECT_TRUE(consistent) << count << " items on " << threads << " threads";
      EXPECT_TRUE(of_worker[0] == std::thread::id{} || of_worker[0] == caller);
      for (std::size_t i = 0; i < count; ++i) EXPECT_LT(worker_of[i], threads) << i;
      // Distinct workers are distinct threads.
      for (unsigned a = 0; a < threads; ++a)
        for (unsigned b = a + 1; b < threads; ++b)
          if (of_worker[a] != std::thread::id{} && of_worker[b] != std::thread::id{})
            EXPECT_NE(of_worker[a], of_worker[b]) << a << " " << b;
      if (threads == 1) EXPECT_EQ(of_worker[0], caller);
    }
}

}  // namespace
}  // namespace swath::base
