// base::give_back_freed_memory(): what a process freed and keep_freed_memory() kept goes back to
// the system once the resident memory is above the limit, and stays while it is below.
// base::heap_on_huge_pages(): the heap the next allocations come from, the caller's and that of
// parallel_for()'s threads, is marked for transparent huge pages (read back from the kernel's
// /proc/self/smaps).
#include "swath/base/freed_memory.hpp"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "swath/base/parallel.hpp"

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

// The kernel's THPeligible of the mapping holding `address` (-1: not found, or no such field).
int huge_page_eligible(const void* address) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-' &&
        line.find(':') > line.find(' ')) {
      inside = begin <= at && at < end;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

// The kernel's mode for transparent huge pages ("always", "madvise", "never"; "": unknown).
[[maybe_unused]] std::string huge_page_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text;
  std::getline(in, text);
  const std::size_t open = text.find('['), close = text.find(']');
  return open == std::string::npos || close == std::string::npos
             ? std::string{}
             : text.substr(open + 1, close - open - 1);
}

// The checks of the test below, in a process of their own: exit 0 when they hold, else the
// number of the first that fails (a heap other tests fragmented and trimmed first would put the
// block marked among its free chunks, not at its top, where a fresh process's plan grows).
[[noreturn, maybe_unused]] void check_huge_heap_pages() {
  constexpr std::size_t kBlock = 8 << 20;
  keep_freed_memory();
  heap_on_huge_pages();
  char* mine = static_cast<char*>(std::malloc(kBlock));
  if (mine == nullptr || huge_page_eligible(mine + kBlock / 2) != 1) std::_Exit(1);
  std::free(mine);
  // A thread parallel_for() starts allocates from another heap (glibc's arena per thread). Each
  // item waits for the other to start, so that the two run on the two threads.
  int helper_eligible = -2;
  std::atomic<int> started{0};
  parallel_for(2, 2, [&](std::size_t, unsigned worker) {
    ++started;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (started < 2 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
    if (worker != 1) return;
    char* its = static_cast<char*>(std::malloc(kBlock));
    helper_eligible = its != nullptr ? huge_page_eligible(its + kBlock / 2) : -3;
    std::free(its);
  });
  std::_Exit(helper_eligible == 1 || helper_eligible == -2 ? 0 : 2);
}

TEST(FreedMemory, HeapOnHugePagesMarksTheCallersAndParallelThreadsHeaps) {
#if !defined(__GLIBC__) || defined(SWATH_FREED_MEMORY_SANITIZED)
  GTEST_SKIP() << "glibc's allocator only (sanitizers bring their own)";
#else
  if (huge_page_mode() != "madvise")
    GTEST_SKIP() << "the kernel gives huge pages always or never: nothing to mark";
  // The test's own measure tells marked memory from the rest: a plain mapping is not eligible.
  constexpr std::size_t kBlock = 8 << 20;
  void* plain = ::mmap(nullptr, kBlock, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(plain, MAP_FAILED);
  const int plain_eligible = huge_page_eligible(static_cast<char*>(plain) + kBlock / 2);
  ::munmap(plain, kBlock);
  if (plain_eligible < 0) GTEST_SKIP() << "no THPeligible in /proc/self/smaps";
  ASSERT_EQ(plain_eligible, 0);
  // "threadsafe": the child runs the test binary anew, its heap fresh.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(check_huge_heap_pages(), ::testing::ExitedWithCode(0), "")
      << "1: the caller's heap not marked; 2: a parallel_for thread's";
#endif
}

}  // namespace
}  // namespace swath::base
