#pragma once
// Sorting a few doubles as std::sort does, without its calls.

#include <algorithm>

namespace swath::geometry {

/// std::sort(first, last) for a handful of values (a leg's cuts: mostly 2 to 4): libstdc++ sorts
/// up to 16 values by its insertion sort alone, which this is step for step (a value below the
/// first moves to the front, any other down past the greater ones before it), so the order is
/// std::sort's bit for bit (-0 and 0 among equal values, NaN, included), without its two calls
/// (most of sorting a leg's cuts). More than 16: std::sort itself.
inline void sort_few(double* first, double* last) {
  if (last - first > 16) return std::sort(first, last);
  if (last - first < 2) return;  // nothing to sort; nor first + 1 of a null first
  for (double* i = first + 1; i != last; ++i) {
    const double v = *i;
    if (v < *first) {
      std::move_backward(first, i, i + 1);
      *first = v;
    } else {
      double* j = i;
      for (; v < j[-1]; --j) *j = j[-1];
      *j = v;
    }
  }
}

}  // namespace swath::geometry
