#include "swath/geometry/polygon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "random_polygons.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::geometry {
namespace {

Ring regular_polygon(std::size_t n, double r) {
  Ring ring;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * double(i) / double(n);
    ring.push_back({r * std::cos(t), r * std::sin(t)});
  }
  return ring;
}

TEST(Area, RectangleTriangleAndRegularPolygonMatchClosedForms) {
  EXPECT_DOUBLE_EQ(signed_area({{0, 0}, {30, 0}, {30, 20}, {0, 20}}), 600.0);
  EXPECT_DOUBLE_EQ(signed_area({{0, 0}, {0, 20}, {30, 20}, {30, 0}}), -600.0);
  EXPECT_DOUBLE_EQ(signed_area({{1, 1}, {5, 1}, {1, 4}}), 6.0);
  for (std::size_t n : {3u, 5u, 8u, 100u}) {
    const double expected = double(n) / 2.0 * 100.0 * std::sin(2 * std::numbers::pi / double(n));
    EXPECT_NEAR(signed_area(regular_polygon(n, 10.0)), expected, 1e-9 * expected) << n;
  }
}

TEST(Area, HolesAreSubtractedWhateverTheirOrientation) {
  Polygon p{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {{{10, 10}, {10, 30}, {30, 30}, {30, 10}}}};
  EXPECT_DOUBLE_EQ(area(p), 10000.0 - 400.0);
  p.holes[0] = {{10, 10}, {30, 10}, {30, 30}, {10, 30}};
  EXPECT_DOUBLE_EQ(area(p), 9600.0);
}

TEST(Area, ShoelaceAgreesWithTrapezoidFormulaOnRandomPolygons) {
  test::Rng rng(11);
  for (int k = 0; k < 200; ++k) {
    const Ring ring =
        test::transformed(test::random_star_polygon(rng, 5 + k % 40, 50, 400), k * 7.0, 1e5, -3e5);
    double trapezoid = 0.0;  // independent: sum of signed trapezoids under each edge
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      trapezoid += (a.x - b.x) * (a.y + b.y) / 2.0;
    }
    EXPECT_NEAR(signed_area(ring), trapezoid, 1e-6 * std::abs(trapezoid));
  }
}

TEST(Perimeter, SumsEveryRing) {
  EXPECT_DOUBLE_EQ(perimeter(Ring{{0, 0}, {3, 0}, {3, 4}}), 12.0);
  const Polygon p{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{2, 2}, {2, 4}, {4, 4}, {4, 2}}}};
  EXPECT_DOUBLE_EQ(perimeter(p), 48.0);
  EXPECT_NEAR(perimeter(regular_polygon(1000, 1.0)), 2 * std::numbers::pi, 1e-4);
}

TEST(Centroid, TriangleIsMeanOfVertices) {
  const Point2 c = centroid(Polygon{{{0, 0}, {6, 0}, {0, 9}}, {}});
  EXPECT_NEAR(c.x, 2.0, 1e-12);
  EXPECT_NEAR(c.y, 3.0, 1e-12);
}

TEST(Centroid, LShapeByDecomposition) {
  // 20x10 rectangle plus 10x10 square on top of its left half.
  const Polygon l{{{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}}, {}};
  const Point2 c = centroid(l);
  EXPECT_NEAR(c.x, (200 * 10.0 + 100 * 5.0) / 300, 1e-12);
  EXPECT_NEAR(c.y, (200 * 5.0 + 100 * 15.0) / 300, 1e-12);
}

TEST(Centroid, HoleShiftsItAway) {
  const Polygon p{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{6, 4}, {6, 6}, {8, 6}, {8, 4}}}};
  const Point2 c = centroid(p);
  EXPECT_NEAR(c.x, (100 * 5.0 - 4 * 7.0) / 96, 1e-12);
  EXPECT_NEAR(c.y, 5.0, 1e-12);
}

TEST(Centroid, MatchesRasterisedCentroidOnRandomPolygons) {
  test::Rng rng(5);
  for (int k = 0; k < 20; ++k) {
    const Ring ring = test::random_star_polygon(rng, 12, 30, 100);
    double sx = 0, sy = 0, count = 0;
    for (double x = -100; x < 100; x += 0.5)
      for (double y = -100; y < 100; y += 0.5)
        if (locate_point({x + 0.25, y + 0.25}, ring) == Containment::inside) {
          sx += x + 0.25;
          sy += y + 0.25;
          ++count;
        }
    const Point2 c = centroid(Polygon{ring, {}});
    EXPECT_NEAR(c.x, sx / count, 0.1);
    EXPECT_NEAR(c.y, sy / count, 0.1);
    EXPECT_NEAR(area(Polygon{ring, {}}), count * 0.25, 0.01 * area(Polygon{ring, {}}));
  }
}

TEST(NormaliseRing, DropsClosingAndRepeatedVerticesAndOrients) {
  const Ring clockwise_closed{{0, 0}, {0, 10}, {0, 10}, {10, 10}, {10, 0}, {0, 0}, {0, 0}};
  const NormalisedRing n = normalise_ring(clockwise_closed, true);
  EXPECT_EQ(n.ring, (Ring{{0, 0}, {10, 0}, {10, 10}, {0, 10}}));
  EXPECT_EQ(n.source_index, (std::vector<std::size_t>{0, 4, 3, 1}));
  EXPECT_GT(signed_area(n.ring), 0);
  const NormalisedRing h = normalise_ring(n.ring, false);
  EXPECT_LT(signed_area(h.ring), 0);
  EXPECT_EQ(h.ring.front(), (Point2{0, 0}));
}

}  // namespace
}  // namespace swath::geometry
