// base::give_back_freed_memory(): what a process freed and keep_freed_memory() kept goes back to
// the system once the resident memory is above the limit, and stays while it is below.
#include "swath/base/freed_memory.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace swath::base {
namespace {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(hwaddress_sanitizer) || \
    __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define SWATH_FREED_MEMORY_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_HWADDRESS__) || defined(__SANITIZE_THREAD__)
#define SWATH_FREED_MEMORY_SANITIZED 1
#endif

TEST(FreedMemory, GivenBackAboveTheLimitKeptBelow) {
#if !defined(__GLIBC__) || defined(SWATH_FREED_MEMORY_SANITIZED)
  GTEST_SKIP() << "glibc's allocator only (sanitizers bring their own)";
#else
  keep_freed_memory();
  constexpr std::size_t kBlock = 2 << 20, kMiB = 1 << 20;
  std::vector<char*> blocks;
  for (int i = 0; i < 48; ++i) {  // 96 MiB from the heap (below the 32 MiB mmap threshold each)
    blocks.push_back(static_cast<char*>(std::malloc(kBlock)));
    ASSERT_NE(blocks.back(), nullptr);
    std::memset(blocks.back(), i + 1, kBlock);
  }
  const volatile char* last = blocks.back();  // kept: the freed ones are not the heap's top
  for (std::size_t i = 0; i + 1 < blocks.size(); ++i) std::free(blocks[i]);
  const std::size_t kept = resident_bytes();
  ASSERT_GT(kept, 94 * kMiB);
  EXPECT_FALSE(give_back_freed_memory(kept + 64 * kMiB));
  EXPECT_GT(resident_bytes(), kept - 8 * kMiB) << "nothing given back below the limit";
  EXPECT_TRUE(give_back_freed_memory(kept - 64 * kMiB));
  EXPECT_LT(resident_bytes(), kept - 80 * kMiB) << "the 94 MiB freed given back";
  EXPECT_EQ(last[kBlock - 1], 48);  // the block still held is as written
  std::free(blocks.back());
#endif
}

}  // namespace
}  // namespace swath::base
