#pragma once
// Independent pieces of work spread over threads, with results that do not depend on how many.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <type_traits>
#include <vector>

#include "swath/base/freed_memory.hpp"

namespace swath::base {

/// The machine's hardware threads, at least 1: the default of every `threads` below.
inline unsigned machine_threads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

/// Calls f(i) once for each i in [0, count), on up to `threads` threads (0: machine_threads()),
/// the calling thread one of them; items are handed out in index order. Each f(i) must write only
/// what is its own (e.g. slot i of a vector sized beforehand): then the results are the same for
/// any number of threads. When calls throw, the exception of the lowest index is rethrown after
/// every thread has ended (items after it are not started), so that too does not depend on the
/// number of threads.
///
/// f may also take (i, worker): `worker` is which thread calls it, 0 the calling thread, always
/// below `threads` (resolved), for state a thread keeps to itself (a cache, a scratch buffer).
template <typename F>
void parallel_for(std::size_t count, unsigned threads, F&& f) {
  if (threads == 0) threads = machine_threads();
  const std::size_t workers = std::min<std::size_t>(threads, count);
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> failed_at{count};  // the lowest index that threw, count: none
  std::exception_ptr failure;
  std::mutex lock;
  const auto work = [&](unsigned worker) {
    for (std::size_t i; (i = next++) < count && i < failed_at;) {
      try {
        if constexpr (std::is_invocable_v<F&, std::size_t, unsigned>)
          f(i, worker);
        else
          f(i);
      } catch (...) {
        const std::lock_guard<std::mutex> guard(lock);
        if (i < failed_at) {
          failed_at = i;
          failure = std::current_exception();
        }
      }
    }
  };
  std::vector<std::thread> helpers;
  for (std::size_t k = 1; k < workers; ++k) {
    try {
      helpers.emplace_back([&work, k] {
        thread_heap_started();
        work(unsigned(k));
      });
    } catch (const std::system_error&) {  // no thread to be had: fewer do the work
      break;
    }
  }
  work(0u);
  for (std::thread& t : helpers) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace swath::base
