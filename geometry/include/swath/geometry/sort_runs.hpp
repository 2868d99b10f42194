#pragma once
// Sorting sequences that mostly come in order already: a polygon's vertices or boundary samples
// in ring order rise and fall in long stretches, and sorting them anew for every candidate lane
// direction was a large part of planning --concave split on long outlines.

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace swath::geometry {

/// Sorts `v` by `less` (a strict weak order) with the result std::sort(v.begin(), v.end(), less)
/// gives: the runs already in order (non-decreasing, or strictly decreasing and reversed) are
/// merged pairwise when there are few (at most one per 8 elements), else v is sorted whole. Where
/// two elements are equivalent (neither less) std::sort's order between them is its own, so
/// unless `equivalents_alike` (equivalent elements are the same value, e.g. equal points) the
/// merged result is checked and v sorted whole from its first order when two are equivalent.
template <typename T, typename Less>
void sort_by_runs(std::vector<T>& v, Less less, bool equivalents_alike) {
  struct Run {
    std::size_t begin, end;
    bool decreasing;
  };
  std::vector<Run> runs;
  const std::size_t most = v.size() / 8;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i + 1;
    const bool decreasing = j < v.size() && less(v[j], v[i]);
    if (decreasing)
      while (j < v.size() && less(v[j], v[j - 1])) ++j;
    else
      while (j < v.size() && !less(v[j], v[j - 1])) ++j;
    runs.push_back({i, j, decreasing});
    if (runs.size() > most) break;  // too many: no need to count on
    i = j;
  }
  if (runs.size() > most) {
    std::sort(v.begin(), v.end(), less);
    return;
  }
  // Merged pass by pass between v and one buffer (std::merge, stable as inplace_merge is): one
  // allocation, where inplace_merge took a fresh buffer for every merge (fresh pages, for the
  // 10,000-vertex outlines a direction search sorts ~100 times).
  std::vector<T> first_order;
  if (!equivalents_alike) first_order = v;
  for (const Run& r : runs)
    if (r.decreasing)
      std::reverse(v.begin() + std::ptrdiff_t(r.begin), v.begin() + std::ptrdiff_t(r.end));
  std::vector<std::size_t> bounds{0};
  for (const Run& r : runs) bounds.push_back(r.end);
  std::vector<T> other(bounds.size() > 2 ? v.size() : 0);
  std::vector<T>* from = &v;
  std::vector<T>* to = &other;
  while (bounds.size() > 2) {
    const auto at = [](std::vector<T>& w, std::size_t k) { return w.begin() + std::ptrdiff_t(k); };
    std::vector<std::size_t> merged{0};
    for (std::size_t k = 0; k + 1 < bounds.size(); k += 2)
      if (k + 2 < bounds.size()) {
        std::merge(at(*from, bounds[k]), at(*from, bounds[k + 1]), at(*from, bounds[k + 1]),
                   at(*from, bounds[k + 2]), at(*to, bounds[k]), less);
        merged.push_back(bounds[k + 2]);
      } else {
        std::copy(at(*from, bounds[k]), at(*from, bounds[k + 1]), at(*to, bounds[k]));
        merged.push_back(bounds[k + 1]);
      }
    bounds = std::move(merged);
    std::swap(from, to);
  }
  if (from != &v) v.swap(other);
  if (equivalents_alike) return;
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    if (!less(v[i], v[i + 1])) {  // sorted, so equivalent: std::sort's own order between them
      v = std::move(first_order);
      std::sort(v.begin(), v.end(), less);
      return;
    }
}

}  // namespace swath::geometry
