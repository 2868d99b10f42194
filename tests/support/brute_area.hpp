#pragma once
// VisibilityRouter's area queries before its segment index, over every edge of every ring: the
// truth the index and the lazy search are checked against (tests/geometry/segment_index_test.cpp,
// visibility_search_test.cpp). Exact predicates, no pruning.

#include <algorithm>
#include <cmath>
#include <vector>

#include "swath/geometry/predicates.hpp"
#include "swath/geometry/visibility.hpp"

namespace swath::test {

class BruteArea {
 public:
  explicit BruteArea(std::vector<geometry::Ring> rings) : rings_(std::move(rings)) {
    double extent = 0;
    for (const geometry::Ring& ring : rings_)
      for (const geometry::Point2& p : ring)
        extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    tolerance_ = 1e-9 * (1 + extent);
  }
  bool contains(geometry::Point2 p) const {
    int count = 0;
    for (const geometry::Ring& ring : rings_) {
      const geometry::Containment c = geometry::locate_point(p, ring);
      if (c == geometry::Containment::on_boundary) return true;
      count += c == geometry::Containment::inside;
    }
    if (count % 2 == 1) return true;
    for (const geometry::Ring& ring : rings_)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const geometry::Point2 a = ring[i], d = ring[(i + 1) % ring.size()] - a;
        const double t = std::clamp(geometry::dot(p - a, d) / geometry::dot(d, d), 0.0, 1.0);
        if (geometry::distance(p, a + d * t) <= tolerance_) return true;
      }
    return false;
  }
  double length_outside(geometry::Point2 a, geometry::Point2 b) const {
    const geometry::Point2 d = b - a;
    const double len2 = geometry::dot(d, d);
    if (len2 == 0) return 0.0;
    std::vector<double> cuts{0.0, 1.0};
    for (const geometry::Ring& ring : rings_)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const geometry::Point2 p = ring[i], q = ring[(i + 1) % ring.size()];
        // An edge's end within rounding of the leg's line cuts there (the router's rule).
        const double off_line_limit = tolerance_ * std::sqrt(len2);
        const bool p_on = std::abs(geometry::cross(d, p - a)) <= off_line_limit,
                   q_on = std::abs(geometry::cross(d, q - a)) <= off_line_limit;
        if (p_on) cuts.push_back(std::clamp(geometry::dot(p - a, d) / len2, 0.0, 1.0));
        if (q_on) cuts.push_back(std::clamp(geometry::dot(q - a, d) / len2, 0.0, 1.0));
        if ((p_on && q_on) || !geometry::segments_intersect(a, b, p, q)) continue;
        const double denom = geometry::cross(d, q - p);
        if (denom != 0) {
          cuts.push_back(std::clamp(geometry::cross(p - a, q - p) / denom, 0.0, 1.0));
        } else {
          cuts.push_back(std::clamp(geometry::dot(p - a, d) / len2, 0.0, 1.0));
          cuts.push_back(std::clamp(geometry::dot(q - a, d) / len2, 0.0, 1.0));
        }
      }
    std::sort(cuts.begin(), cuts.end());
    double outside = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      if (cuts[k + 1] <= cuts[k]) continue;
      if (!contains(a + d * ((cuts[k] + cuts[k + 1]) / 2))) outside += (cuts[k + 1] - cuts[k]);
    }
    return outside * std::sqrt(len2);
  }
  bool visible(geometry::Point2 a, geometry::Point2 b) const {
    return length_outside(a, b) <= 1e-9 * (1 + geometry::distance(a, b));
  }

 private:
  std::vector<geometry::Ring> rings_;
  double tolerance_ = 0;
};

}  // namespace swath::test
