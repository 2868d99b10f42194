// apps::BlockCache (apps/swath/block_cache.hpp) against malloc and free themselves (the reference):
// every block it gives holds what was asked, aligned as malloc's, and never overlaps another live
// block, whichever cache takes it back; it keeps at most a class's bytes and hands everything back
// when released.
#include "block_cache.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <set>
#include <vector>

#if defined(__GLIBC__)

namespace swath::apps {
namespace {

struct Live {
  unsigned char* block;
  std::size_t bytes;
  unsigned char fill;
};

// What malloc promises of a block of `bytes`: room for them, at malloc's alignment.
void expect_as_malloc(const void* block, std::size_t bytes) {
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(block) % alignof(std::max_align_t), 0u);
  EXPECT_GE(malloc_usable_size(const_cast<void*>(block)), bytes);
}

std::unique_ptr<BlockCache> empty_cache() {
  auto cache = std::make_unique<BlockCache>();  // value-initialised: all zero, as a thread_local
  cache->state = BlockCache::kOpen;             // as swath's operator delete opens it
  return cache;
}

TEST(BlockCache, RandomTakesAndGivesOverSeveralCachesAsMallocWould) {
  for (const unsigned seed : {1u, 2u, 3u, 52u}) {
    std::mt19937 random(seed);
    std::vector<std::unique_ptr<BlockCache>> caches;
    for (int k = 0; k < 3; ++k) caches.push_back(empty_cache());
    std::vector<Live> live;
    std::uniform_int_distribution<std::size_t> small(0, 1100), large(1000, 70000);
    for (int step = 0; step < 20000; ++step) {
      BlockCache& cache = *caches[random() % caches.size()];  // blocks move between caches
      if (live.empty() || random() % 100 < 52) {
        const std::size_t bytes = random() % 20 == 0 ? large(random) : small(random);
        auto* block = static_cast<unsigned char*>(cache.take(bytes));
        expect_as_malloc(block, bytes);
        const auto fill = static_cast<unsigned char>(random());
        std::memset(block, fill, bytes);
        live.push_back({block, bytes, fill});
      } else {
        const std::size_t k = random() % live.size();
        const Live gone = live[k];
        live[k] = live.back();
        live.pop_back();
        // Untouched since taken: no other block was given the same bytes.
        for (std::size_t i = 0; i < gone.bytes; ++i)
          ASSERT_EQ(gone.block[i], gone.fill) << "seed " << seed << " step " << step;
        cache.give(gone.block);
      }
    }
    std::set<const unsigned char*> distinct;
    for (const Live& l : live) {
      for (std::size_t i = 0; i < l.bytes; ++i) ASSERT_EQ(l.block[i], l.fill) << "seed " << seed;
      EXPECT_TRUE(distinct.insert(l.block).second);
      caches[0]->give(l.block);
    }
    for (auto& cache : caches) {
      std::size_t kept_bytes = 0;
      for (std::size_t c = 1; c < BlockCache::kClasses; ++c) {
        EXPECT_LE(cache->count[c] * BlockCache::class_bytes(c), BlockCache::kClassBytes);
        kept_bytes += cache->count[c] * BlockCache::class_bytes(c);
      }
      EXPECT_LE(kept_bytes, 16u << 20);
      cache->release(true);
    }
  }
}

TEST(BlockCache, ClassesAtTheirEdges) {
  auto cache = empty_cache();
  // The smallest chunk serves up to 24 bytes; then a class per 16 bytes, up to 1,032.
  for (const std::size_t bytes : {0u, 1u, 8u, 24u, 25u, 40u, 41u, 56u, 1016u, 1017u, 1032u}) {
    void* block = cache->take(bytes);
    expect_as_malloc(block, bytes);
    const std::size_t c = BlockCache::class_of(bytes);
    EXPECT_GE(BlockCache::class_bytes(c), bytes);
    if (c > 1) EXPECT_LT(BlockCache::class_bytes(c - 1), bytes);
    cache->give(block);
    EXPECT_EQ(cache->count[c], 1u) << bytes;
    EXPECT_EQ(cache->take(bytes), block) << bytes;  // the same block back: the class it was
    EXPECT_EQ(cache->count[c], 0u);
    cache->give(block);
    cache->release(false);
  }
  // Beyond the classes: straight back to free, nothing kept.
  void* block = cache->take(BlockCache::kMaxBytes + 1);
  expect_as_malloc(block, BlockCache::kMaxBytes + 1);
  cache->give(block);
  for (std::size_t c = 0; c < BlockCache::kClasses; ++c) EXPECT_EQ(cache->count[c], 0u);
  cache->give(nullptr);  // as free(nullptr)
}

TEST(BlockCache, BlocksFromMallocOfAnySizeServeTheirClass) {
  // A block malloc gave for another size (or with a larger chunk than asked) goes to the class its
  // usable size can hold, and serves every request mapped to that class.
  auto cache = empty_cache();
  for (std::size_t bytes = 0; bytes <= BlockCache::kMaxBytes; ++bytes) {
    void* block = std::malloc(bytes);
    const std::size_t usable = malloc_usable_size(block);
    cache->give(block);
    // A larger chunk than asked, or (ASan, valgrind) fewer bytes than class 1's: freed, none kept.
    if (usable < BlockCache::kMinBytes || usable > BlockCache::kMaxBytes) {
      for (std::size_t k = 0; k < BlockCache::kClasses; ++k) ASSERT_EQ(cache->count[k], 0u);
      continue;
    }
    std::size_t c = 1;
    while (c < BlockCache::kClasses && cache->count[c] == 0) ++c;
    ASSERT_LT(c, BlockCache::kClasses) << bytes;
    EXPECT_LE(BlockCache::class_bytes(c), usable) << bytes;
    // The largest request of that class fits the block.
    EXPECT_EQ(cache->take(BlockCache::class_bytes(c)), block) << bytes;
    std::memset(block, 0x5a, BlockCache::class_bytes(c));
    std::free(block);
  }
}

TEST(BlockCache, KeepsAtMostAClassesBytesAndNothingOnceClosed) {
  auto cache = empty_cache();
  const std::size_t c = BlockCache::class_of(100);
  const std::size_t cap = BlockCache::kClassBytes / BlockCache::class_bytes(c);
  std::vector<void*> blocks;  // of exactly the class's bytes (malloc may give a larger chunk)
  while (blocks.size() < cap + 10) {
    void* block = cache->take(100);
    if (malloc_usable_size(block) == BlockCache::class_bytes(c))
      blocks.push_back(block);
    else
      std::free(block);
  }
  for (void* block : blocks) cache->give(block);
  EXPECT_EQ(cache->count[c], cap);
  cache->release(true);
  EXPECT_EQ(cache->count[c], 0u);
  EXPECT_EQ(cache->head[c], nullptr);
  void* block = cache->take(100);
  expect_as_malloc(block, 100);
  cache->give(block);  // closed: freed at once
  EXPECT_EQ(cache->count[c], 0u);
}

TEST(BlockCache, KeepsNoBlockBelowTheFirstClassOrAboveTheLast) {
  // glibc's usable sizes are at least 24, but ASan, valgrind and libc_malloc_debug report the bytes
  // asked: below 8 the class would wrap around, 8 to 23 would fall in the unused class 0.
  auto cache = empty_cache();
  for (const std::size_t usable : {0u, 1u, 7u, 8u, 9u, 16u, 23u, 1033u, 1040u, 4096u}) {
    cache->give(std::malloc(1040), usable);  // room for any of them
    for (std::size_t c = 0; c < BlockCache::kClasses; ++c) ASSERT_EQ(cache->count[c], 0u) << usable;
  }
  // The edges themselves are kept, in the first and the last class.
  cache->give(std::malloc(1040), BlockCache::kMinBytes);
  EXPECT_EQ(cache->count[1], 1u);
  cache->give(std::malloc(1040), BlockCache::kMaxBytes);
  EXPECT_EQ(cache->count[BlockCache::kClasses - 1], 1u);
  cache->release(true);
}

TEST(BlockCache, KeepsNothingUntilOpened) {
  BlockCache cache{};  // all zero, as a thread's before its first delete
  void* block = cache.take(100);
  expect_as_malloc(block, 100);
  cache.give(block);
  for (std::size_t c = 0; c < BlockCache::kClasses; ++c) EXPECT_EQ(cache.count[c], 0u);
}

}  // namespace
}  // namespace swath::apps

#endif
