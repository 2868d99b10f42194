#pragma once
// A thread's small freed blocks, kept for its next allocations of the same size.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace swath::base {

/// The small blocks (up to kMaxBytes) a thread frees, kept by size class for its next allocations
/// instead of handed back to malloc; every block comes from malloc and goes back to it when its
/// class is full or the cache is released. Meant as the back of a program's operator new and
/// delete, one per thread (all zero: an empty cache, no constructor needed).
///
/// Why: a plan allocates ~80,000 blocks, nearly all below 1 KiB, most of them freed by the thread
/// that made them (vectors and maps of one candidate direction). glibc's own per-thread cache
/// keeps only 7 blocks of a size, so a loop that frees a hundred then allocates a hundred goes
/// through its bins; its fast path is ~150 instructions a malloc and free, this one's ~30.
///
/// A block's class is found again from malloc_usable_size(), which is at least what was asked:
/// class c holds blocks of at least 16 c + 8 bytes (malloc's chunks grow 16 bytes at a time and
/// give 8 of their bytes less), so any block of a class serves any request mapped to it.
/// Without glibc the cache is never used (take() and give() go straight to malloc and free).
struct BlockCache {
  static constexpr std::size_t kClasses = 65;                        // class 0 unused
  static constexpr std::size_t kMaxBytes = 16 * (kClasses - 1) + 8;  // 1,032: glibc's tcache's
  /// At most this many bytes kept per class (so at most 16 MiB a thread in all).
  static constexpr std::size_t kClassBytes = 256 * 1024;

  void* head[kClasses];  // each free block's first 8 bytes point to the next one of its class
  std::uint32_t count[kClasses];
  bool closed;  // released at the thread's end: everything goes straight to malloc and free

  static constexpr std::size_t class_of(std::size_t bytes) {
    return bytes <= 24 ? 1 : (bytes + 7) >> 4;
  }
  static constexpr std::size_t class_bytes(std::size_t c) { return 16 * c + 8; }

  /// A block of at least `bytes` bytes, aligned as malloc's; nullptr where malloc fails.
  void* take(std::size_t bytes) {
#if defined(__GLIBC__)
    if (bytes <= kMaxBytes) {
      const std::size_t c = class_of(bytes);
      if (void* block = head[c]) {
        head[c] = *static_cast<void**>(block);
        --count[c];
        return block;
      }
      return std::malloc(class_bytes(c));
    }
#endif
    return std::malloc(bytes);
  }

  /// Takes back a block from take() (or from malloc), of any thread's cache.
  void give(void* block) {
#if defined(__GLIBC__)
    if (block == nullptr) return;
    const std::size_t usable = malloc_usable_size(block);
    if (usable <= kMaxBytes && !closed) {
      const std::size_t c = (usable - 8) >> 4;
      if ((count[c] + 1) * class_bytes(c) <= kClassBytes) {
        *static_cast<void**>(block) = head[c];
        head[c] = block;
        ++count[c];
        return;
      }
    }
#endif
    std::free(block);
  }

  /// Hands every kept block back to malloc; with `close`, keeps none from now on.
  void release(bool close) {
    for (std::size_t c = 0; c < kClasses; ++c) {
      while (void* block = head[c]) {
        head[c] = *static_cast<void**>(block);
        std::free(block);
      }
      count[c] = 0;
    }
    closed = closed || close;
  }
};

}  // namespace swath::base
