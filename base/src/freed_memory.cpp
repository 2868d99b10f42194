#include "swath/base/freed_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace swath::base {

void keep_freed_memory() {
#if defined(__GLIBC__)
  // Fixed values also switch off glibc's own threshold adjustment, which rose only after each
  // first free of a larger block and so still gave most buffers fresh pages.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's upper limit on 64-bit
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace swath::base
