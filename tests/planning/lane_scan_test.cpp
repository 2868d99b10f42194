// LaneScan::at(y) looks only at the edges of y's bucket. It must answer exactly what the crossing
// rule answers over every edge: checked against that rule on random areas with holes (fixed
// seeds), integer grids full of horizontal and collinear edges, at directions along the edges,
// for ordinates through vertices, at the area's bottom and top, between and beyond.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "lane_scan.hpp"
#include "random_polygons.hpp"

namespace swath::planning::detail {
namespace {

// The crossing rule over every edge: the truth.
std::vector<Span> all_edges_at(const LaneScan& scan, double y) {
  std::vector<double> xs;
  for (const auto& [a, b] : scan.edges())
    if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
  std::sort(xs.begin(), xs.end());
  std::vector<Span> out;
  for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
    if (xs[i + 1] - xs[i] > 1e-6) out.push_back({xs[i], xs[i + 1]});
  return out;
}

std::vector<Ring> scan_test_area(test::Rng& rng, int k) {
  if (k % 4 == 3) return {test::random_grid_ring(rng, 40, 12), test::random_grid_ring(rng, 12, 12)};
  std::vector<Ring> rings{test::random_field_polygon(rng, std::size_t(20) << (k % 4) * 3, 500)};
  for (int h = 0; h < 5 * (k % 3); ++h) {  // rectangles: horizontal edges at shared ordinates
    const double x = -300 + 75.0 * (h % 8), y = -300 + 75.0 * (h / 8);
    rings.push_back({{x, y}, {x, y + 20}, {x + 25, y + 20}, {x + 25, y}});
  }
  return rings;
}

TEST(LaneScan, BucketsAnswerAsEveryEdge) {
  test::Rng rng(2024);
  std::size_t spans = 0;
  for (int k = 0; k < 16; ++k) {
    const std::vector<Ring> rings = scan_test_area(rng, k);
    std::uniform_real_distribution<double> any_angle(0, 180);
    for (const double angle : {0.0, 90.0, 30.0, any_angle(rng)}) {
      const LaneScan scan(rings, angle);
      std::vector<double> ys{scan.y_min, scan.y_max, scan.y_min - 1, scan.y_max + 1,
                             (scan.y_min + scan.y_max) / 2};
      for (const auto& [a, b] : scan.edges()) {  // through every vertex, and a hair either side
        ys.push_back(a.y);
        ys.push_back(std::nextafter(a.y, -1e300));
        ys.push_back(std::nextafter(a.y, 1e300));
      }
      std::uniform_real_distribution<double> inside(scan.y_min, scan.y_max);
      for (int q = 0; q < 500; ++q) ys.push_back(inside(rng));
      for (const double y : ys) {
        const std::vector<Span> fast = scan.at(y), truth = all_edges_at(scan, y);
        ASSERT_EQ(fast.size(), truth.size()) << "area " << k << " angle " << angle << " y " << y;
        for (std::size_t i = 0; i < fast.size(); ++i) {
          ASSERT_EQ(fast[i].x0, truth[i].x0);
          ASSERT_EQ(fast[i].x1, truth[i].x1);
        }
        spans += truth.size();
      }
    }
  }
  EXPECT_GT(spans, 50000u);  // the queries mostly cut the area
}

}  // namespace
}  // namespace swath::planning::detail
