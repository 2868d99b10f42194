#include "swath/geometry/visibility.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "brute_area.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/sort_few.hpp"

namespace swath::geometry {
namespace {

// A random area for the leg tests: every fourth a grid ring, with `combs` every fourth from the
// third a comb, else a field with six star holes.
std::vector<Ring> random_area(test::Rng& rng, int area, bool combs) {
  if (area % 4 == 3) return {test::random_grid_ring(rng, 30, 10)};
  if (combs && area % 4 == 2)
    return {test::transformed(test::comb_polygon(7, 10, 40, 10), 13.0 * area, 2.0, -3.0)};
  std::vector<Ring> rings{test::random_field_polygon(rng, std::size_t(20) << area % 3, 400)};
  for (int h = 0; h < 6; ++h) {
    Ring star = test::transformed(test::random_star_polygon(rng, 6, 5, 20), 0, -150 + 60.0 * h,
                                  40.0 * (h % 3) - 40);
    std::reverse(star.begin(), star.end());
    rings.push_back(star);
  }
  return rings;
}

// 100 x 100 square with a tall hole x in [40, 60], y in [20, 80].
VisibilityRouter square_with_hole() {
  return VisibilityRouter(
      {{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {{40, 20}, {40, 80}, {60, 80}, {60, 20}}});
}

TEST(VisibilityRouter, GoesAroundAHoleAlongTheShortestSide) {
  const VisibilityRouter r = square_with_hole();
  EXPECT_FALSE(r.visible({20, 50}, {80, 50}));
  const auto path = r.path({20, 50}, {80, 50});
  // Around either end of the hole: 2 x |(20,50)-(40,80)| + 20.
  EXPECT_NEAR(polyline_length(path), 2 * std::hypot(20.0, 30.0) + 20, 1e-9);
  ASSERT_EQ(path.size(), 4u);
  for (std::size_t i = 0; i + 1 < path.size(); ++i) EXPECT_TRUE(r.visible(path[i], path[i + 1]));
  // A clear leg stays straight; a leg along the boundary is inside.
  EXPECT_EQ(r.path({10, 10}, {90, 10}).size(), 2u);
  EXPECT_TRUE(r.visible({0, 0}, {100, 0}));
  EXPECT_TRUE(r.visible({40, 20}, {40, 80}));
}

TEST(VisibilityRouter, ContainsIsInsideTheClosedAreaNotAZeroLengthLeg) {
  const VisibilityRouter r = square_with_hole();
  EXPECT_TRUE(r.contains({20, 50}));
  EXPECT_TRUE(r.contains({0, 50}));      // on the outer boundary
  EXPECT_TRUE(r.contains({40, 50}));     // on the hole's boundary
  EXPECT_FALSE(r.contains({50, 50}));    // in the hole
  EXPECT_FALSE(r.contains({-60, -40}));  // outside, where a home is
  // The mistake this guards against: a leg of length 0 is "visible" wherever it is.
  EXPECT_TRUE(r.visible({-60, -40}, {-60, -40}));
}

// contains() casts its ray to the left or to the right of the point, whichever way the edge index
// holds fewer edges: the same answer as every edge of every ring asked (the brute-force area), for
// points anywhere, on vertices (the ray through them), on edges, a rounding error off them, and
// level with vertices (rays along edges), on random areas with holes and on grid rings (fixed
// seed).
TEST(VisibilityRouter, ContainsIsTheBruteForceAreasAnswer) {
  test::Rng rng(5252);
  std::size_t inside = 0, outside = 0;
  for (int area = 0; area < 16; ++area) {
    const std::vector<Ring> rings = random_area(rng, area, false);
    const test::BruteArea brute(rings);
    const VisibilityRouter router(rings, Routing::measure_only);
    std::vector<Point2> vertices;
    for (const Ring& ring : rings) vertices.insert(vertices.end(), ring.begin(), ring.end());
    double extent = 0;
    for (const Point2& v : vertices) extent = std::max({extent, std::abs(v.x), std::abs(v.y)});
    std::uniform_real_distribution<double> unit(0, 1), coordinate(-1.2 * extent, 1.2 * extent);
    std::uniform_int_distribution<std::size_t> pick(0, vertices.size() - 1);
    for (int k = 0; k < 3000; ++k) {
      const Point2 v = vertices[pick(rng)], w = vertices[pick(rng)];
      Point2 p;
      switch (k % 6) {
        case 0:
          p = v;
          break;
        case 1:
          p = v + (w - v) * unit(rng);  // on a chord between two vertices
          break;
        case 2:
          p = {coordinate(rng), v.y};  // level with a vertex
          break;
        case 3:
          p = {std::nextafter(v.x, INFINITY), std::nextafter(v.y, -INFINITY)};
          break;
        default:
          p = {coordinate(rng), coordinate(rng)};
      }
      const bool expected = brute.contains(p);
      ASSERT_EQ(router.contains(p), expected)
          << "area " << area << " point (" << p.x << ", " << p.y << ")";
      (expected ? inside : outside) += 1;
    }
  }
  // Both answers are asked about often.
  EXPECT_GT(inside, 10000u);
  EXPECT_GT(outside, 10000u);
}

// The leg test (visible(), length_outside()) asks the edges near the leg only, inlined, and a
// visibility test asks the longest piece between cuts first, stopping when it alone is past the
// tolerance: the answers are those of cutting the leg by every edge and summing its pieces
// outside in order (the brute-force area), bit for bit. Legs between vertices (the router's
// nodes: cuts at both ends), along edges, short legs about a boundary point (within rounding of
// it), from a hair off a vertex and at random.
TEST(VisibilityRouter, LegsAreMeasuredAsOverEveryEdge) {
  test::Rng rng(5253);
  std::size_t clear = 0, blocked = 0;
  for (int area = 0; area < 12; ++area) {
    const std::vector<Ring> rings = random_area(rng, area, true);
    const test::BruteArea brute(rings);
    const VisibilityRouter router(rings, Routing::measure_only);
    std::vector<std::pair<Point2, Point2>> edges;
    for (const Ring& ring : rings)
      for (std::size_t i = 0; i < ring.size(); ++i)
        edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
    double extent = 0;
    for (const auto& [v, w] : edges) extent = std::max({extent, std::abs(v.x), std::abs(v.y)});
    std::uniform_real_distribution<double> unit(0, 1), coordinate(-1.2 * extent, 1.2 * extent),
        hair(-3e-10, 3e-10);
    std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
    for (int k = 0; k < 4000; ++k) {
      const auto [v, v_next] = edges[pick(rng)];
      const Point2 w = edges[pick(rng)].first;
      Point2 a = v, b = w;  // k % 6 == 0: vertex to vertex
      switch (k % 6) {
        case 1:  // along an edge, beyond its ends or short of them
          a = v + (v_next - v) * (2 * unit(rng) - 0.5);
          b = v + (v_next - v) * (2 * unit(rng) - 0.5);
          break;
        case 2: {  // about a point of an edge or a vertex, by less than the tolerance
          const Point2 on = v + (v_next - v) * (unit(rng) < 0.5 ? 0.0 : unit(rng));
          a = on + Point2{hair(rng), hair(rng)};
          b = on + Point2{hair(rng), hair(rng)};
          break;
        }
        case 3:  // from a hair off a vertex to a point on a chord
          a = {std::nextafter(v.x, INFINITY), std::nextafter(v.y, -INFINITY)};
          b = v + (w - v) * unit(rng);
          break;
        case 4:
          a = {coordinate(rng), coordinate(rng)};
          break;
        case 5:
          a = {coordinate(rng), coordinate(rng)};
          b = {coordinate(rng), coordinate(rng)};
          break;
      }
      const double outside_m = brute.length_outside(a, b);
      const bool visible = brute.visible(a, b);
      ASSERT_EQ(router.length_outside(a, b), outside_m)
          << "area " << area << " leg (" << a.x << ", " << a.y << ") (" << b.x << ", " << b.y
          << ")";
      ASSERT_EQ(router.visible(a, b), visible) << "area " << area << " leg (" << a.x << ", " << a.y
                                               << ") (" << b.x << ", " << b.y << ")";
      (visible ? clear : blocked) += 1;
    }
  }
  // Both answers are asked about often.
  EXPECT_GT(clear, 10000u);
  EXPECT_GT(blocked, 10000u);
}

TEST(VisibilityRouter, LengthOutsideCountsHolesAndTheOutside) {
  const VisibilityRouter r = square_with_hole();
  EXPECT_NEAR(r.length_outside({-10, 50}, {110, 50}), 10 + 20 + 10, 1e-9);
  EXPECT_NEAR(r.length_outside({20, 50}, {80, 50}), 20, 1e-9);
  EXPECT_NEAR(r.length_outside({50, -50}, {50, 150}), 50 + 60 + 50, 1e-9);
  // The diagonal crosses the hole from (40, 40) to (60, 60).
  EXPECT_NEAR(r.length_outside({5, 5}, {95, 95}), 20 * std::sqrt(2.0), 1e-9);
}

// A comb's teeth point down with their tips on one line; a leg from a point of one tip to the far
// corner of another runs along both tips and across the gap's mouth between them, outside the
// area for the mouth's length (closed form). Rotated and moved so that rounding puts the computed
// points a hair to either side of the tips' line: found on a corpus comb, where 602 of 1,001 such
// legs were "inside" (0 m outside) and a drone's share was timed with a leg home across the gap.
TEST(VisibilityRouter, ALegAlongCollinearToothTipsIsOutsideAcrossTheGap) {
  std::mt19937_64 rng(1818);
  std::uniform_real_distribution<double> angle(0, 2 * std::acos(-1.0)), size(20, 120),
      offset(-500, 500), along(0, 1);
  for (int shape = 0; shape < 40; ++shape) {
    const double tooth = size(rng), gap = size(rng), depth = 2 * size(rng), base = size(rng) / 2;
    const double theta = angle(rng), c = std::cos(theta), s = std::sin(theta);
    const Point2 shift{offset(rng), offset(rng)};
    const auto place = [&](Point2 p) {
      return Point2{c * p.x - s * p.y + shift.x, s * p.x + c * p.y + shift.y};
    };
    // Counter-clockwise: the base on top, two teeth down to y = 0, the gap between them.
    const double right = 2 * tooth + gap;
    const Ring ring = {place({right, depth + base}),
                       place({0, depth + base}),
                       place({0, 0}),
                       place({tooth, 0}),
                       place({tooth, depth}),
                       place({tooth + gap, depth}),
                       place({tooth + gap, 0}),
                       place({right, 0})};
    const VisibilityRouter r({ring});
    const Point2 corner = ring[2], tip_start = ring[6], tip_end = ring[7];
    for (int k = 0; k < 25; ++k) {
      const Point2 e = tip_start + (tip_end - tip_start) * along(rng);
      EXPECT_FALSE(r.visible(e, corner)) << "shape " << shape << " point " << k;
      EXPECT_NEAR(r.length_outside(e, corner), gap, 1e-6 * (1 + gap)) << "shape " << shape;
      // Along one tip the leg runs on the boundary: inside.
      EXPECT_TRUE(r.visible(e, tip_end)) << "shape " << shape << " point " << k;
    }
  }
}

TEST(VisibilityRouter, UShapeRoutesOverTheNotchFloor) {
  // U opening upwards; from the top of one arm to the top of the other, around the notch corners.
  const VisibilityRouter r(
      {{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}}});
  const auto path = r.path({5, 25}, {25, 25});
  EXPECT_NEAR(polyline_length(path), 2 * std::hypot(5.0, 15.0) + 10, 1e-9);
}

TEST(VisibilityRouter, AMeasuringRouterDoesNotRoute) {
  const VisibilityRouter r(
      {{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}}},
      Routing::measure_only);
  EXPECT_FALSE(r.routes());
  EXPECT_EQ(r.path({5, 25}, {25, 25}).size(), 2u);
  EXPECT_NEAR(r.length_outside({5, 25}, {25, 25}), 10, 1e-9);
}

}  // namespace
}  // namespace swath::geometry

namespace swath::geometry {
namespace {

// sort_few() must leave a leg's cuts as std::sort leaves them, bit for bit: random lengths 0-24
// (past 16: std::sort itself), values from a few (many equal) with -0 and 0 mixed, and NaN now
// and then (libstdc++'s insertion moves a value below the first to the front past a NaN).
TEST(SortFew, TheOrderOfStdSortBitForBit) {
  test::Rng rng(5259);
  std::uniform_int_distribution<int> length(0, 24), value(-3, 3), sign(0, 1), nan(0, 40);
  std::size_t signed_zeros = 0, nans = 0;
  for (int k = 0; k < 20000; ++k) {
    std::vector<double> xs(std::size_t(length(rng)));
    for (double& x : xs) {
      const int v = value(rng);
      x = v == 0 ? (sign(rng) ? -0.0 : 0.0) : v + (k % 2 ? 0.0 : 0.25 * value(rng));
      if (k % 4 == 3 && nan(rng) == 0) x = std::numeric_limits<double>::quiet_NaN();
    }
    std::vector<double> truth = xs;
    std::sort(truth.begin(), truth.end());
    sort_few(xs.data(), xs.data() + xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(xs[i]), std::bit_cast<std::uint64_t>(truth[i]))
          << "case " << k << " at " << i;
      signed_zeros += xs[i] == 0 && std::signbit(xs[i]);
      nans += std::isnan(xs[i]);
    }
  }
  EXPECT_GT(signed_zeros, 1000u);  // the test sees -0 among equal values
  EXPECT_GT(nans, 500u);
}

}  // namespace
}  // namespace swath::geometry
