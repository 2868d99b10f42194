#pragma once
// The nodes a shortest-path search has not settled yet, laid out for the look at all of them.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// The open nodes of a search (VisibilityRouter::path with a corner allowance: each node it
/// settles looks for onward legs to every one of them), in no order, with their coordinates and
/// h side by side (structure of arrays), so that legs() computes their f two at a time.
class OpenNodes {
 public:
  /// The nodes `open` (indices of `nodes`, each at most once) as the open nodes, node u with h
  /// `h_of[u]`; `n`: the number of nodes.
  void reset(const std::vector<std::size_t>& open, std::size_t n, const std::vector<Point2>& nodes,
             const std::vector<double>& h_of) {
    list_.assign(open.begin(), open.end());
    x_.resize(list_.size());
    y_.resize(list_.size());
    h_.resize(list_.size());
    at_.resize(n);
    for (std::size_t k = 0; k < list_.size(); ++k) {
      at_[list_[k]] = std::uint32_t(k);
      x_[k] = nodes[list_[k]].x;
      y_[k] = nodes[list_[k]].y;
      h_[k] = h_of[list_[k]];
    }
  }
  /// Node v (open) settled: no longer open. The last place moves into its place.
  void remove(std::size_t v) {
    const std::uint32_t k = at_[v], moved = list_.back();
    list_[k] = moved;
    x_[k] = x_.back();
    y_[k] = y_.back();
    h_[k] = h_.back();
    at_[moved] = k;
    list_.pop_back();
    x_.pop_back();
    y_.pop_back();
    h_.pop_back();
  }
  std::size_t size() const { return list_.size(); }

  /// The legs from point c (reached at g) on to every open node u: through = g + |c u| and f =
  /// through + h(u), bit for bit as g + distance(c, u) and that + h(u) (a difference's square does
  /// not depend on its sign, and IEEE sums, products and square roots round alike in vector
  /// registers). That holds while the compiler fuses no multiply-add in distance() (the build
  /// targets plain x86-64, which has none; tests/geometry/open_nodes_test.cpp would fail on a
  /// target that has). Afterwards under() lists the places (into node(), through(), f()) of the
  /// legs of f <= cut, in order. Returns the least f above cut (infinity: none).
  double legs(Point2 c, double g, double cut) {
    const std::size_t m = list_.size();
    through_.resize(m + 1);  // + 1: the branch-free append below writes one place past the end
    f_.resize(m + 1);
    under_.resize(m + 1);
    const double *x = x_.data(), *y = y_.data(), *h = h_.data();
    double *through = through_.data(), *f = f_.data();
    std::uint32_t* under = under_.data();
    std::size_t count = 0, k = 0;
    double least_above = std::numeric_limits<double>::infinity();
#if defined(__SSE2__)
    const __m128d cx = _mm_set1_pd(c.x), cy = _mm_set1_pd(c.y), g2 = _mm_set1_pd(g),
                  cut2 = _mm_set1_pd(cut),
                  infinity2 = _mm_set1_pd(std::numeric_limits<double>::infinity());
    __m128d least2 = infinity2;
    for (; k + 2 <= m; k += 2) {
      const __m128d dx = _mm_sub_pd(_mm_loadu_pd(x + k), cx),
                    dy = _mm_sub_pd(_mm_loadu_pd(y + k), cy);
      const __m128d leg =
          _mm_add_pd(g2, _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy))));
      const __m128d sum = _mm_add_pd(leg, _mm_loadu_pd(h + k));
      _mm_storeu_pd(through + k, leg);
      _mm_storeu_pd(f + k, sum);
      const __m128d in = _mm_cmple_pd(sum, cut2);
      least2 = _mm_min_pd(least2, _mm_or_pd(_mm_and_pd(in, infinity2), _mm_andnot_pd(in, sum)));
      const int mask = _mm_movemask_pd(in);
      under[count] = std::uint32_t(k);
      count += std::size_t(mask & 1);
      under[count] = std::uint32_t(k + 1);
      count += std::size_t(mask >> 1);
    }
    double pair[2];
    _mm_storeu_pd(pair, least2);
    least_above = std::min(pair[0], pair[1]);
#endif
    for (; k < m; ++k) {
      const double dx = x[k] - c.x, dy = y[k] - c.y;
      through[k] = g + std::sqrt(dx * dx + dy * dy);
      f[k] = through[k] + h[k];
      if (f[k] <= cut)
        under[count++] = std::uint32_t(k);
      else
        least_above = std::min(least_above, f[k]);
    }
    under_.resize(count);
    return least_above;
  }
  const std::vector<std::uint32_t>& under() const {
    return under_;
  }
  std::uint32_t node(std::size_t place) const {
    return list_[place];
  }
  double through(std::size_t place) const {
    return through_[place];
  }
  double f(std::size_t place) const {
    return f_[place];
  }

 private:
  std::vector<std::uint32_t> list_;   ///< the open nodes
  std::vector<double> x_, y_, h_;     ///< per place of list_: its node's coordinates and h
  std::vector<std::uint32_t> at_;     ///< per node of list_, its place there
  std::vector<double> through_, f_;   ///< per place, filled by legs()
  std::vector<std::uint32_t> under_;  ///< places of f <= the cut, filled by legs()
};

}  // namespace swath::geometry
