#include "swath/geometry/regularity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

#include "random_polygons.hpp"

namespace swath::geometry {
namespace {

TEST(Regularity, RegularPolygonsScoreOne) {
  for (std::size_t n : {3u, 4u, 6u, 17u}) {
    Ring ring;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = 2 * std::numbers::pi * double(i) / double(n) + 0.3;
      ring.push_back({100 * std::cos(t), 100 * std::sin(t)});
    }
    const Regularity r = regularity(ring);
    EXPECT_NEAR(r.angle, 1.0, 1e-12) << n;
    EXPECT_NEAR(r.edge, 1.0, 1e-12) << n;
    EXPECT_NEAR(r.overall, 1.0, 1e-12) << n;
  }
}

TEST(Regularity, RectangleClosedForm) {
  // All angles 90°: angle regularity 1. Edges a, b, a, b around mean (a+b)/2:
  // edge regularity = 1 - |a - b| / (a + b).
  const double a = 300, b = 100;
  const Regularity r = regularity({{0, 0}, {a, 0}, {a, b}, {0, b}});
  EXPECT_NEAR(r.angle, 1.0, 1e-12);
  EXPECT_NEAR(r.edge, 1.0 - (a - b) / (a + b), 1e-12);
  EXPECT_NEAR(r.overall, (1.0 + 1.0 - (a - b) / (a + b)) / 2, 1e-12);
}

TEST(Regularity, LShapeClosedForm) {
  // Angles 90 x5 and 270: mean 120, deviations 30 x5 + 150 = 300 -> 1 - (300/360)/6.
  // Edges 20,10,10,10,10,20: mean 80/6, deviations sum = 2(20 - 40/3) + 4(40/3 - 10) = 80/3.
  const Regularity r = regularity({{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}});
  EXPECT_NEAR(r.angle, 1.0 - (300.0 / 360.0) / 6.0, 1e-12);
  EXPECT_NEAR(r.edge, 1.0 - ((80.0 / 3.0) / (80.0 / 6.0)) / 6.0, 1e-12);
}

TEST(Regularity, InteriorAnglesSumToPolygonTotalAndIgnoreOrientation) {
  test::Rng rng(8);
  for (int k = 0; k < 100; ++k) {
    Ring ring = test::random_star_polygon(rng, 3 + k % 25, 20, 100);
    const std::vector<double> angles = interior_angles_deg(ring);
    const double sum = std::accumulate(angles.begin(), angles.end(), 0.0);
    EXPECT_NEAR(sum, (double(ring.size()) - 2) * 180.0, 1e-9);
    const Regularity forward = regularity(ring);
    std::reverse(ring.begin(), ring.end());
    const Regularity backward = regularity(ring);
    EXPECT_NEAR(forward.overall, backward.overall, 1e-12);
    EXPECT_LE(forward.overall, 1.0);
  }
}

}  // namespace
}  // namespace swath::geometry
