#pragma once
// A min-heap for searches that take few of the items they queue.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace swath::geometry {

/// No lead key: every item compared whole (CappedHeap's default).
struct NoLead {
  template <class T>
  double operator()(const T&) const {
    return 0.0;
  }
};

/// Gives items back least first (by T's operator<), as a min-heap does, but keeps only the least
/// of them in the heap: the others wait unsorted. A search that takes about one item in ten it
/// queues (VisibilityRouter::path: the rest lie beyond its answer) so saves most of the heap's
/// work. When the heap runs dry, the least eighth of the waiting items (at least 64) moves in and
/// the greatest of them becomes the cap. Every item in the heap is <= the cap <= every item
/// waiting, so the items come out in the order one heap gives (equal items in either order).
///
/// The items stay where they were pushed; the heap and the waiting list move 16-byte entries of
/// an item's index and its lead key, `Lead{}(item)`, a double that orders items as far as it goes
/// (x < y wherever lead(x) < lead(y)): entries of different leads are ordered by them alone, of
/// equal leads by their items (a search's items are 40 bytes, compared field by field, and their
/// first field, f, mostly differs).
template <class T, class Lead = NoLead>
class CappedHeap {
 public:
  /// Empties the heap; `lowest` must not be above any item pushed until the first pop (every
  /// item waits until then).
  void clear(const T& lowest) {
    heap_.clear();
    rest_.clear();
    items_.clear();
    cap_ = lowest;
    cap_lead_ = Lead{}(lowest);
  }
  bool empty() const { return heap_.empty() && rest_.empty(); }
  void push(const T& item) {
    const Entry entry{Lead{}(item), std::uint32_t(items_.size())};
    items_.push_back(item);
    if (cap_lead_ < entry.lead || (!(entry.lead < cap_lead_) && cap_ < item)) {
      rest_.push_back(entry);
      return;
    }
    // Up from a new leaf while less than its parent, as std::push_heap does (here inline: a
    // search's entries mostly stay at the leaf, and the call cost more than the steps).
    std::size_t hole = heap_.size();
    heap_.push_back(entry);
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 2;
      if (!Greater{this}(heap_[parent], entry)) break;
      heap_[hole] = heap_[parent];
      hole = parent;
    }
    heap_[hole] = entry;
  }
  /// The least item, removed. Not on an empty heap.
  T pop() {
    if (heap_.empty()) refill();
    std::pop_heap(heap_.begin(), heap_.end(), Greater{this});
    const T least = items_[heap_.back().index];
    heap_.pop_back();
    return least;
  }

 private:
  struct Entry {
    double lead;
    std::uint32_t index;  ///< in items_
  };
  /// x > y in the items' order (the heap's comparison: a min-heap).
  struct Greater {
    const CappedHeap* heap;
    bool operator()(const Entry& x, const Entry& y) const {
      if (x.lead != y.lead) return y.lead < x.lead;
      return heap->items_[y.index] < heap->items_[x.index];
    }
  };
  void refill() {
    const std::size_t k = std::min(rest_.size(), std::max<std::size_t>(64, rest_.size() / 8));
    const auto from = rest_.end() - std::ptrdiff_t(k);  // the k least, after nth_element
    std::nth_element(rest_.begin(), from, rest_.end(), Greater{this});
    cap_ = items_[from->index];
    cap_lead_ = from->lead;
    heap_.assign(from, rest_.end());
    rest_.erase(from, rest_.end());
    std::make_heap(heap_.begin(), heap_.end(), Greater{this});
  }
  std::vector<Entry> heap_, rest_;
  std::vector<T> items_;  ///< every item pushed since clear(), in order
  T cap_{};
  double cap_lead_ = 0;
};

}  // namespace swath::geometry
