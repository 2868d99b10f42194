#include "swath/geometry/convex_hull.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "random_polygons.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::geometry {
namespace {

// Brute force: p is a hull vertex iff it lies neither strictly inside a triangle of other points
// nor on a segment between two of them.
bool is_extreme(const std::vector<Point2>& pts, std::size_t k) {
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = 0; j < pts.size(); ++j) {
      if (i == k || j == k || pts[i] == pts[k] || pts[j] == pts[k]) continue;
      // p strictly inside segment i-j (collinear, between) is not extreme
      if (orientation(pts[i], pts[j], pts[k]) == Orientation::collinear &&
          segments_intersect(pts[i], pts[j], pts[k], pts[k]))
        return false;
      for (std::size_t m = 0; m < pts.size(); ++m) {
        if (m == k || pts[m] == pts[k]) continue;
        const auto a = orientation(pts[i], pts[j], pts[k]);
        const auto b = orientation(pts[j], pts[m], pts[k]);
        const auto c = orientation(pts[m], pts[i], pts[k]);
        if (a != Orientation::collinear && a == b && b == c) return false;
      }
    }
  return true;
}

TEST(ConvexHull, SquareWithInteriorAndEdgePoints) {
  const Ring h = convex_hull({{0, 0}, {1, 1}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}});
  EXPECT_EQ(h, (Ring{{0, 0}, {2, 0}, {2, 2}, {0, 2}}));
}

TEST(ConvexHull, CollinearAndTinyInputs) {
  EXPECT_EQ(convex_hull({{0, 0}, {1, 1}, {2, 2}}), (Ring{{0, 0}, {2, 2}}));
  EXPECT_EQ(convex_hull({{3, 3}, {3, 3}}), (Ring{{3, 3}}));
}

TEST(ConvexHull, EqualsBruteForceExtremePointsOnRandomGrids) {
  test::Rng rng(3);
  for (int k = 0; k < 150; ++k) {
    const Ring pts = test::random_grid_ring(rng, 4 + k % 20, 4 + k % 7);
    const Ring hull = convex_hull(pts);
    std::vector<Point2> brute;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (is_extreme(pts, i)) brute.push_back(pts[i]);
    auto lex = [](Point2 a, Point2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
    Ring sorted_hull = hull;
    std::sort(sorted_hull.begin(), sorted_hull.end(), lex);
    std::sort(brute.begin(), brute.end(), lex);
    if (brute.size() >= 3) {
      EXPECT_EQ(sorted_hull, brute) << "case " << k;
    }
    // Every input point is inside or on the hull; the hull turns strictly left.
    if (hull.size() >= 3) {
      for (const Point2& p : pts) EXPECT_NE(locate_point(p, hull), Containment::outside);
      for (std::size_t i = 0; i < hull.size(); ++i)
        EXPECT_EQ(orientation(hull[i], hull[(i + 1) % hull.size()], hull[(i + 2) % hull.size()]),
                  Orientation::counter_clockwise);
    }
  }
}

}  // namespace
}  // namespace swath::geometry
