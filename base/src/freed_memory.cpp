#include "swath/base/freed_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <unistd.h>

#include <cstdio>

namespace swath::base {

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
