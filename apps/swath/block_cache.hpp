#pragma once
// A thread's small freed blocks, kept for its next allocations of the same size.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// Sanitizers keep their own operator new and delete (a block kept here would hide a use after its
// delete from them): SWATH_BLOCK_CACHE is 1 where swath's operator new and delete use the cache
// (glibc, no sanitizer), else 0. The tests of the real operators skip where it is 0.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(hwaddress_sanitizer) || \
    __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define SWATH_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_HWADDRESS__) || defined(__SANITIZE_THREAD__)
#define SWATH_SANITIZED 1
#endif
#if defined(__GLIBC__) && !defined(SWATH_SANITIZED)
#define SWATH_BLOCK_CACHE 1
#else
#define SWATH_BLOCK_CACHE 0
#endif

namespace swath::apps {

/// The small blocks (up to kMaxBytes) a thread frees, kept by size class for its next allocations
/// instead of handed back to malloc; every block comes from malloc and goes back to it when its
/// class is full or the cache is released. Meant as the back of a program's operator new and
/// delete, one per thread (all zero: an empty cache that keeps nothing until opened, no
/// constructor needed).
///
/// Why: a plan allocates ~80,000 blocks, nearly all below 1 KiB, most of them freed by the thread
/// that made them (vectors and maps of one candidate direction). glibc's own per-thread cache
/// keeps only 7 blocks of a size, so a loop that frees a hundred then allocates a hundred goes
/// through its bins; its fast path is ~150 instructions a malloc and free, this one's ~30.
///
/// Memory: a thread keeps at most kClassBytes a class (16 MiB in all at the very most). A kept
/// block serves only its class, so a thread holds the sum of its classes' peaks (each at most the
/// cap), not the peak of their sum, until it ends and the cache is released.
///
/// A block's class is found again from malloc_usable_size(), which is at least what was asked:
/// class c holds blocks of at least 16 c + 8 bytes (malloc's chunks grow 16 bytes at a time and
/// give 8 of their bytes less), so any block of a class serves any request mapped to it.
/// Without glibc the cache is never used (take() and give() go straight to malloc and free).
struct BlockCache {
  static constexpr std::size_t kClasses = 65;                        // class 0 unused
  static constexpr std::size_t kMaxBytes = 16 * (kClasses - 1) + 8;  // 1,032: glibc's tcache's
  static constexpr std::size_t kMinBytes = 24;                       // class 1's
  /// At most this many bytes kept per class.
  static constexpr std::size_t kClassBytes = 256 * 1024;

  /// kUnopened (all zero) until the owner registers the cache for its thread's end; kClosed once
  /// released at that end, or where it cannot be registered. Only an open cache keeps blocks.
  enum State : std::uint8_t { kUnopened = 0, kOpen, kClosed };

  void* head[kClasses];  // each free block's first 8 bytes point to the next one of its class
  std::uint32_t count[kClasses];
  State state;

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
    give(block, malloc_usable_size(block));
#else
    std::free(block);
#endif
  }

  /// give() with the block's malloc_usable_size() (a parameter for the tests: glibc's is at least
  /// 24, but ASan, valgrind and libc_malloc_debug report the bytes asked, which may be 0). A block
  /// below class 1 or above the last class goes straight back to free.
  void give(void* block, std::size_t usable) {
    if (state == kOpen && usable >= kMinBytes && usable <= kMaxBytes) {
      const std::size_t c = (usable - 8) >> 4;
      if ((count[c] + 1) * class_bytes(c) <= kClassBytes) {
        *static_cast<void**>(block) = head[c];
        head[c] = block;
        ++count[c];
        return;
      }
    }
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
    if (close) state = kClosed;
  }
};

}  // namespace swath::apps
