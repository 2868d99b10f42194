#include "swath/geometry/convex_hull.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "field_shapes.hpp"
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

// Melkman's walk over simple rings gives the sorted hull's vertices (as a set, both
// counter-clockwise): random stars and fields (either orientation, any start vertex), combs,
// spirals and the split corpus's outlines, which are full of collinear and nearly collinear runs.
TEST(ConvexHull, MelkmanOnSimpleRingsEqualsTheSortedHull) {
  test::Rng rng(1987);
  std::vector<Ring> rings;
  for (int k = 0; k < 200; ++k) {
    Ring r = k % 2 ? test::random_star_polygon(rng, 3 + std::size_t(k % 60), 50, 400)
                   : test::random_field_polygon(rng, 5 + std::size_t(k % 90), 300);
    if (k % 3 == 0) std::reverse(r.begin(), r.end());
    std::rotate(r.begin(), r.begin() + std::ptrdiff_t(std::size_t(k) % r.size()), r.end());
    rings.push_back(r);
  }
  for (int teeth = 1; teeth <= 6; ++teeth) rings.push_back(test::comb_polygon(teeth, 30, 200, 40));
  for (int arms = 2; arms <= 7; ++arms) rings.push_back(test::spiral_polygon(arms, 500, 90, 30));
  rings.push_back(
      {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2}, {0, 2}, {0, 1}});  // collinear runs
  for (const test::CorpusShape& shape : test::split_corpus(5, 6)) rings.push_back(shape.area.outer);
  for (std::size_t k = 0; k < rings.size(); ++k) {
    Ring melkman = convex_hull_of_simple_ring(rings[k]);
    Ring sorted = convex_hull(rings[k]);
    EXPECT_GT(signed_area(melkman), 0) << k;
    auto lexicographic = [](Point2 a, Point2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
    std::sort(melkman.begin(), melkman.end(), lexicographic);
    std::sort(sorted.begin(), sorted.end(), lexicographic);
    EXPECT_EQ(melkman, sorted) << k;
  }
}

}  // namespace
}  // namespace swath::geometry
