#include "swath/base/freed_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace swath::base {

namespace {

// Set by heap_on_huge_pages(): the heaps of the threads parallel_for() starts are marked too.
std::atomic<bool> huge_heap_pages{false};

// The heap's top grown by a block it then keeps (below M_MMAP_THRESHOLD, and M_TRIM_THRESHOLD
// is not reached: keep_freed_memory()), the whole 2 MiB pages inside it marked for transparent
// huge pages. Untouched, the block costs address space only.
void mark_heap_top() {
#if defined(__GLIBC__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t kBlock_bytes = 30u << 20, kHugePage_bytes = 2u << 20;
  void* const block = std::malloc(kBlock_bytes);
  if (block == nullptr) return;
  const auto at = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t begin = (at + kHugePage_bytes - 1) & ~std::uintptr_t{kHugePage_bytes - 1};
  const std::uintptr_t end = (at + kBlock_bytes) & ~std::uintptr_t{kHugePage_bytes - 1};
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  std::free(block);
#endif
}

}  // namespace

void heap_on_huge_pages() {
  if (const char* env = std::getenv("SWATH_HUGE_PAGES");
      env != nullptr && std::strcmp(env, "0") == 0)
    return;
  mark_heap_top();
  huge_heap_pages = true;
}

void thread_heap_started() {
  if (huge_heap_pages.load(std::memory_order_relaxed)) mark_heap_top();
}

void keep_freed_memory() {
#if defined(__GLIBC__)
  // Fixed values also switch off glibc's own threshold adjustment, which rose only after each
  // first free of a larger block and so still gave most buffers fresh pages.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's upper limit on 64-bit
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  // Heaps grown 16 MiB at a time, not by what each request lacks: the main heap's brk and above
  // all a thread's heap, which without a pad glibc grows one mprotect per few pages (~340 calls,
  // 1 % of a plan's CPU). Address space only: pages are resident once touched, as before.
  mallopt(M_TOP_PAD, 16 << 20);
#endif
}

std::size_t resident_bytes() {
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  if (!statm) return 0;
  unsigned long size_pages = 0, resident_pages = 0;
  const bool read = std::fscanf(statm, "%lu %lu", &size_pages, &resident_pages) == 2;
  std::fclose(statm);
  const long page = ::sysconf(_SC_PAGESIZE);
  return read && page > 0 ? resident_pages * static_cast<std::size_t>(page) : 0;
}

bool give_back_freed_memory(std::size_t limit_bytes) {
#if defined(__GLIBC__)
  if (resident_bytes() <= limit_bytes) return false;
  malloc_trim(0);
  return true;
#else
  (void)limit_bytes;
  return false;
#endif
}

}  // namespace swath::base
