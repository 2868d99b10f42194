// swath's operator new and delete: small blocks through a cache of the thread's
// (apps::BlockCache, which says why); everything else as the library's. Only the swath program
// links this file (a global operator new is the whole program's choice: not the libraries, the
// other programs or the Python module). Every block is malloc's, so a library that frees with
// free() what new gave, or deletes what malloc gave, does no harm.
#include <new>

#include "block_cache.hpp"

#if SWATH_BLOCK_CACHE
#include <pthread.h>

namespace {

using swath::apps::BlockCache;

// Zero-initialised and trivially destructible: no guard on each use. The executable's own
// thread_local, so each use is one load relative to the thread pointer.
thread_local BlockCache cache;

void release_cache(void*) {
  cache.release(true);
}

// Only give() puts blocks in the cache, so a thread's first delete opens it (whether or not the
// thread ever allocated: a thread may only delete what others made). Its cache is handed back to
// malloc at its end, after its thread_local destructors (which may delete): pthread's key
// destructors run after those. Where no key can be had the cache stays closed and keeps nothing.
[[gnu::noinline]] void open_cache() {
  if (cache.state != BlockCache::kUnopened) return;  // closed: stays so
  static const pthread_key_t* const key = [] {
    static pthread_key_t k{};
    return pthread_key_create(&k, release_cache) == 0 ? &k : nullptr;
  }();
  const bool registered = key != nullptr && pthread_setspecific(*key, &cache) == 0;
  cache.state = registered ? BlockCache::kOpen : BlockCache::kClosed;
}

void* allocate(std::size_t bytes) {
  for (;;) {
    if (void* block = cache.take(bytes)) return block;
    // As the library's: the new handler may free memory, else std::bad_alloc.
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

void give(void* block) {
  if (cache.state != BlockCache::kOpen) [[unlikely]]
    open_cache();
  cache.give(block);
}

}  // namespace

void* operator new(std::size_t bytes) {
  return allocate(bytes);
}
void* operator new[](std::size_t bytes) {
  return allocate(bytes);
}
void operator delete(void* block) noexcept {
  give(block);
}
void operator delete[](void* block) noexcept {
  give(block);
}
void operator delete(void* block, std::size_t) noexcept {
  give(block);
}
void operator delete[](void* block, std::size_t) noexcept {
  give(block);
}

#endif
