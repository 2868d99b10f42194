#pragma once
// A min-heap for searches that take few of the items they queue.

#include <algorithm>
#include <cstddef>
#include <functional>
#include <vector>

namespace swath::geometry {

/// Gives items back least first (by T's operator<), as a min-heap does, but keeps only the least
/// of them in the heap: the others wait unsorted. A search that takes about one item in ten it
/// queues (VisibilityRouter::path: the rest lie beyond its answer) so saves most of the heap's
/// work. When the heap runs dry, the least eighth of the waiting items (at least 64) moves in and
/// the greatest of them becomes the cap. Every item in the heap is <= the cap <= every item
/// waiting, so the items come out in the order one heap gives (equal items in either order).
template <class T>
class CappedHeap {
 public:
  /// Empties the heap; `lowest` must not be above any item pushed until the first pop (every
  /// item waits until then).
  void clear(const T& lowest) {
    heap_.clear();
    rest_.clear();
    cap_ = lowest;
  }
  bool empty() const { return heap_.empty() && rest_.empty(); }
  void push(const T& item) {
    if (cap_ < item) {
      rest_.push_back(item);
      return;
    }
    heap_.push_back(item);
    std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
  }
  /// The least item, removed. Not on an empty heap.
  T pop() {
    if (heap_.empty()) refill();
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
    const T least = heap_.back();
    heap_.pop_back();
    return least;
  }

 private:
  void refill() {
    const std::size_t k = std::min(rest_.size(), std::max<std::size_t>(64, rest_.size() / 8));
    const auto from = rest_.end() - std::ptrdiff_t(k);  // the k least, after nth_element
    std::nth_element(rest_.begin(), from, rest_.end(), std::greater<>());
    cap_ = *from;
    heap_.assign(from, rest_.end());
    rest_.erase(from, rest_.end());
    std::make_heap(heap_.begin(), heap_.end(), std::greater<>());
  }
  std::vector<T> heap_, rest_;
  T cap_{};
};

}  // namespace swath::geometry
