// swath's operator new and delete: small blocks through a cache of the thread's
// (base::BlockCache, which says why); everything else as the library's.
#include <new>

#include "swath/base/block_cache.hpp"

// Sanitizers keep their own operator new and delete (a block kept here would hide a use after
// its delete from them).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define SWATH_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SWATH_SANITIZED 1
#endif

#if defined(__GLIBC__) && !defined(SWATH_SANITIZED)
#include <pthread.h>

namespace {

// Zero-initialised and trivially destructible: no guard on each use. The executable's own
// thread_local, so each use is one load relative to the thread pointer.
thread_local swath::base::BlockCache cache;
thread_local bool cache_registered = false;

void release_cache(void*) {
  cache.release(true);
}

// A thread's cache is handed back to malloc at its end, after its thread_local destructors (which
// may delete): pthread's key destructors run after those.
void register_cache() {
  static const pthread_key_t key = [] {
    pthread_key_t k{};
    pthread_key_create(&k, release_cache);
    return k;
  }();
  cache_registered = true;
  pthread_setspecific(key, &cache);
}

void* allocate(std::size_t bytes) {
  if (!cache_registered) register_cache();
  for (;;) {
    if (void* block = cache.take(bytes)) return block;
    // As the library's: the new handler may free memory, else std::bad_alloc.
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

void* operator new(std::size_t bytes) {
  return allocate(bytes);
}
void* operator new[](std::size_t bytes) {
  return allocate(bytes);
}
void operator delete(void* block) noexcept {
  cache.give(block);
}
void operator delete[](void* block) noexcept {
  cache.give(block);
}
void operator delete(void* block, std::size_t) noexcept {
  cache.give(block);
}
void operator delete[](void* block, std::size_t) noexcept {
  cache.give(block);
}

#endif
