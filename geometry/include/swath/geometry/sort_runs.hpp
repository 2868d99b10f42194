#pragma once
// Sorting sequences that mostly come in order already: a polygon's vertices or boundary samples
// in ring order rise and fall in long stretches, and sorting them anew for every candidate lane
// direction was a large part of planning --concave split on long outlines.

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace swath::geometry {

/// A stretch [begin, end) of a sequence already in order by a `less`: non-decreasing, or strictly
/// decreasing (to be reversed).
struct SortedRun {
  std::size_t begin, end;
  bool decreasing;
};

/// The runs of `v` already in order by `less`, front to back, into `runs`; false (and `runs`
/// incomplete) when there are more than one per 8 elements: then sorting whole is cheaper.
template <typename T, typename Less>
bool sorted_runs(const std::vector<T>& v, Less less, std::vector<SortedRun>& runs) {
  runs.clear();
  const std::size_t most = v.size() / 8;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i + 1;
    const bool decreasing = j < v.size() && less(v[j], v[i]);
    if (decreasing)
      while (j < v.size() && less(v[j], v[j - 1])) ++j;
    else
      while (j < v.size() && !less(v[j], v[j - 1])) ++j;
    runs.push_back({i, j, decreasing});
    if (runs.size() > most) return false;  // too many: no need to count on
    i = j;
  }
  return true;
}

/// Sorts `v` by `less` (a strict weak order) with the result std::sort(v.begin(), v.end(), less)
/// gives: the runs already in order (non-decreasing, or strictly decreasing and reversed) are
/// merged pairwise when there are few (at most one per 8 elements), else v is sorted whole. Where
/// two elements are equivalent (neither less) std::sort's order between them is its own, so
/// unless `equivalents_alike` (equivalent elements are the same value, e.g. equal points) the
/// merged result is checked and v sorted whole from its first order when two are equivalent.
template <typename T, typename Less>
void sort_by_runs(std::vector<T>& v, Less less, bool equivalents_alike) {
  std::vector<SortedRun> runs;
  if (!sorted_runs(v, less, runs)) {
    std::sort(v.begin(), v.end(), less);
    return;
  }
  std::vector<T> first_order;
  if (!equivalents_alike) first_order = v;
  const auto at = [&](std::size_t k) { return v.begin() + std::ptrdiff_t(k); };
  std::vector<std::size_t> bounds{0};
  for (const SortedRun& r : runs) {
    if (r.decreasing) std::reverse(at(r.begin), at(r.end));
    bounds.push_back(r.end);
  }
  while (bounds.size() > 2) {
    std::vector<std::size_t> merged{0};
    for (std::size_t k = 0; k + 1 < bounds.size(); k += 2)
      if (k + 2 < bounds.size()) {
        std::inplace_merge(at(bounds[k]), at(bounds[k + 1]), at(bounds[k + 2]), less);
        merged.push_back(bounds[k + 2]);
      } else {
        merged.push_back(bounds[k + 1]);
      }
    bounds = std::move(merged);
  }
  if (equivalents_alike) return;
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    if (!less(v[i], v[i + 1])) {  // sorted, so equivalent: std::sort's own order between them
      v = std::move(first_order);
      std::sort(v.begin(), v.end(), less);
      return;
    }
}

}  // namespace swath::geometry
