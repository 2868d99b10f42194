// swath's own operator new and delete (apps/swath/block_cache_new.cpp, linked into this test as
// into the swath program alone), through the real operators: a thread's kept blocks go back to
// malloc when it ends, also where the thread only deleted what another made; a block may cross
// between new/delete and malloc/free; a fork while another thread allocates leaves the child able
// to allocate. Skipped where the operators are the library's (sanitizers, no glibc).
#include "block_cache.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <thread>
#include <vector>

#if SWATH_BLOCK_CACHE
#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace {

#if SWATH_BLOCK_CACHE

// Bytes malloc has handed out and not had back, over all arenas.
long long heap_in_use() {
  return static_cast<long long>(mallinfo2().uordblks);
}

constexpr std::size_t kBlocksPerThread = 1000;  // ~100 KiB a thread, below a class's cap
constexpr std::size_t kBlockBytes = 100;

struct Block {
  unsigned char bytes[kBlockBytes];
};

// `threads` threads, each deleting (only deleting: no allocation of its own before) blocks the
// calling thread made; the heap in use after they ended, less before.
long long heap_growth_of_threads_that_only_delete(std::size_t threads) {
  const long long before = heap_in_use();
  {
    std::vector<std::vector<Block*>> blocks(threads);
    std::vector<std::thread> running;
    running.reserve(threads);
    for (auto& of_thread : blocks) {
      of_thread.reserve(kBlocksPerThread);
      for (std::size_t k = 0; k < kBlocksPerThread; ++k) of_thread.push_back(new Block);
    }
    for (auto& of_thread : blocks)
      running.emplace_back([&of_thread] {
        for (Block* block : of_thread) delete block;
      });
    for (auto& thread : running) thread.join();
  }
  return heap_in_use() - before;
}

TEST(BlockCacheNew, ThreadsThatOnlyDeleteHandTheirBlocksBackAtTheirEnd) {
  // Each thread's first allocator call is a delete: its cache must still be handed back when it
  // ends, else each thread keeps its ~100 KiB and the heap grows with the number of threads.
  const long long few = heap_growth_of_threads_that_only_delete(5);
  const long long many = heap_growth_of_threads_that_only_delete(50);
  const long long one_thread = kBlocksPerThread * kBlockBytes;
  EXPECT_LT(few, one_thread) << "5 threads";
  EXPECT_LT(many, one_thread) << "50 threads: " << many << " bytes more in use, 5 threads: " << few;
}

TEST(BlockCacheNew, AnEndedThreadsBlocksAreHandedBack) {
  const long long before = heap_in_use();
  std::thread([] {
    std::vector<Block*> blocks;
    blocks.reserve(kBlocksPerThread);
    for (std::size_t k = 0; k < kBlocksPerThread; ++k) blocks.push_back(new Block);
    for (Block* block : blocks) delete block;  // kept by the thread's cache while it lives
    // ~100 KiB kept: the heap still holds them.
    if (heap_in_use() < static_cast<long long>(kBlocksPerThread * kBlockBytes)) std::abort();
  }).join();
  EXPECT_LT(heap_in_use() - before, static_cast<long long>(kBlocksPerThread * kBlockBytes / 10));
}

TEST(BlockCacheNew, BlocksCrossBetweenNewDeleteAndMallocFree) {
  // A library that frees with free() what new gave, or deletes what malloc gave: every block is
  // malloc's, so both are harmless (not valid C++, but done by C libraries holding C++ objects).
  for (std::size_t bytes = 0; bytes <= 2 * swath::apps::BlockCache::kMaxBytes; bytes += 7) {
    void* from_new = ::operator new(bytes);
    std::free(from_new);
    void* from_malloc = std::malloc(bytes);
    ::operator delete(from_malloc);
  }
  void* block = ::operator new(64);  // the cache still serves
  ::operator delete(block);
}

TEST(BlockCacheNew, AForkWhileAnotherThreadAllocatesLeavesTheChildAbleToAllocate) {
  std::atomic<bool> stop{false};
  std::thread busy([&stop] {
    std::vector<std::vector<int>*> held;
    for (std::size_t k = 0; !stop.load(std::memory_order_relaxed); ++k) {
      held.push_back(new std::vector<int>(k % 300));
      if (held.size() > 64) {
        for (auto* v : held) delete v;
        held.clear();
      }
    }
    for (auto* v : held) delete v;
  });
  for (int round = 0; round < 20; ++round) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      alarm(20);  // a child stuck on a lock the other thread held ends by SIGALRM: a failure
      std::vector<std::vector<int>*> made;
      for (std::size_t k = 0; k < 5000; ++k) made.push_back(new std::vector<int>(k % 400));
      for (auto* v : made) delete v;
      _exit(0);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "round " << round;
  }
  stop = true;
  busy.join();
}

#else

TEST(BlockCacheNew, SkippedWhereTheLibrarysOperatorsAreKept) {
  GTEST_SKIP() << "sanitizers or no glibc: swath keeps the library's operator new and delete";
}

#endif

}  // namespace
