// A point's fan (VisibilityRouter::fan_of: the area's edges by their direction from the point, in
// bins of angle) only chooses which edges the exact tests look at. Checked on random areas with
// holes, integer grid rings (collinear edges) and combs (fixed seeds), from vertices, corners,
// points on edges, a hair off vertices and at random: the fan holds the same edges in the same
// bins as the straightforward construction (two diamond angles per edge, std::floor, every bin
// index wrapped by division), and a leg's length outside and visibility through the fan are those
// of every edge asked (the brute-force area), bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "brute_area.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/visibility.hpp"

namespace swath::geometry {

// The router's private fan and the leg test that takes it, for this test only.
struct VisibilityRouterTestProbe {
  static auto fan_of(const VisibilityRouter& r, Point2 a) { return r.fan_of(a); }
  static double outside_m(const VisibilityRouter& r, Point2 a, Point2 b,
                          const decltype(r.fan_of(a))& fan) {
    return r.outside_fraction(a, b, std::numeric_limits<double>::infinity(), &fan) *
           std::sqrt(dot(b - a, b - a));
  }
  static bool visible(const VisibilityRouter& r, Point2 a, Point2 b,
                      const decltype(r.fan_of(a))& fan) {
    return r.visible_with(a, b, &fan);
  }
  /// A fan's items (start.back() of them) as a vector.
  template <class Fan>
  static std::vector<std::uint32_t> items(const Fan& fan) {
    return {fan.items.get(), fan.items.get() + fan.start.back()};
  }
  static std::size_t nodes(const VisibilityRouter& r) { return r.nodes_.size(); }
  static signed char known(const VisibilityRouter& r, std::size_t i, std::size_t j) {
    return r.nodes_known(i, j);
  }
  static bool hidden_bit(const VisibilityRouter& r, std::size_t i, std::size_t j) {
    return r.hidden_bit(i, j);
  }
  static std::size_t bins(const VisibilityRouter& r) { return r.fan_bins_; }
  static double bins_per_unit(const VisibilityRouter& r) { return r.bins_per_unit_; }
  static double extent_m(const VisibilityRouter& r) { return r.extent_m_; }
};

namespace {

using Probe = VisibilityRouterTestProbe;

// The fan as first written: per edge, the diamond angles of both ends and its range of bins
// through std::floor, every bin index wrapped by division.
struct ReferenceFan {
  std::vector<std::uint32_t> start, items, near;
};

double reference_diamond(double dx, double dy) {
  if (dy >= 0) return dx >= 0 ? dy / (dx + dy) : 1 - dx / (dy - dx);
  return dx < 0 ? 2 - dy / (-dx - dy) : 3 + dx / (dx - dy);
}

ReferenceFan reference_fan(const VisibilityRouter& r, const std::vector<Ring>& rings, Point2 a) {
  constexpr double kMargin = 1e-7;
  std::vector<std::pair<Point2, Point2>> edges;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i)
      edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
  const std::size_t fan_bins = Probe::bins(r);
  const long bins = long(fan_bins);
  const auto bin = [&](double angle) { return long(std::floor(angle * Probe::bins_per_unit(r))); };
  const auto wrapped = [bins](long k) { return std::size_t(((k % bins) + bins) % bins); };
  ReferenceFan fan;
  const double near_m = 1e-6 * (1 + std::max({Probe::extent_m(r), std::abs(a.x), std::abs(a.y)}));
  std::vector<std::pair<long, long>> range(edges.size(), {1, 0});
  std::vector<std::uint32_t> count(fan_bins + 1, 0);
  for (std::uint32_t e = 0; e < edges.size(); ++e) {
    const auto [p, q] = edges[e];
    const double x0 = std::min(p.x, q.x), x1 = std::max(p.x, q.x), y0 = std::min(p.y, q.y),
                 y1 = std::max(p.y, q.y);
    const bool far = a.x < x0 - 2 * near_m || a.x > x1 + 2 * near_m || a.y < y0 - 2 * near_m ||
                     a.y > y1 + 2 * near_m;
    if (!far && distance_to_segment(a, p, q) <= near_m) {
      fan.near.push_back(e);
      continue;
    }
    const double tp = reference_diamond(p.x - a.x, p.y - a.y),
                 tq = reference_diamond(q.x - a.x, q.y - a.y);
    double turn = tq - tp;
    if (turn > 2)
      turn -= 4;
    else if (turn < -2)
      turn += 4;
    const long lo = bin(std::min(tp, tp + turn) - kMargin);
    const long hi = bin(std::max(tp, tp + turn) + kMargin);
    range[e] = {lo, std::min(hi, lo + bins - 1)};
    for (long k = lo; k <= range[e].second; ++k) ++count[wrapped(k) + 1];
  }
  for (std::size_t k = 0; k < fan_bins; ++k) count[k + 1] += count[k];
  fan.start = count;
  fan.items.resize(count.back());
  for (std::uint32_t e = 0; e < edges.size(); ++e)
    for (long k = range[e].first; k <= range[e].second; ++k) fan.items[count[wrapped(k)]++] = e;
  return fan;
}

// Areas: a field with rectangle and star holes, integer grid rings, a comb (tips in line).
std::vector<Ring> area(test::Rng& rng, int k) {
  switch (k % 4) {
    case 0:
    case 1: {
      std::vector<Ring> rings{test::random_field_polygon(rng, std::size_t(16) << k % 3, 500)};
      for (int h = 0; h < 4 + 3 * k; ++h) {
        const double x = -300 + 75.0 * (h % 8), y = -300 + 75.0 * (h / 8);
        Ring hole = h % 3 == 2
                        ? test::transformed(test::random_star_polygon(rng, 7, 5, 15), 0, x + 12, y)
                        : Ring{{x + 25, y}, {x + 25, y + 20}, {x, y + 20}, {x, y}};
        std::reverse(hole.begin(), hole.end());
        rings.push_back(hole);
      }
      return rings;
    }
    case 2:
      return {test::random_grid_ring(rng, 30, 10)};
    default:
      return {test::transformed(test::comb_polygon(7, 10, 40, 10), 17.0 * k, 3.0 * k, -2.0 * k)};
  }
}

// Points a fan is asked from or towards: vertices, points on edges, a hair off a vertex, points
// level with a vertex, random points (some outside, some beyond the area's extent).
std::vector<Point2> points(test::Rng& rng, const std::vector<Ring>& rings, int count) {
  std::vector<Point2> vertices;
  double extent = 0;
  for (const Ring& ring : rings)
    for (const Point2& v : ring) {
      vertices.push_back(v);
      extent = std::max({extent, std::abs(v.x), std::abs(v.y)});
    }
  std::uniform_real_distribution<double> unit(0, 1), coordinate(-1.1 * extent, 1.1 * extent);
  std::uniform_int_distribution<std::size_t> pick(0, vertices.size() - 1);
  std::vector<Point2> out;
  for (int k = 0; k < count; ++k) {
    const Point2 v = vertices[pick(rng)], w = vertices[pick(rng)];
    switch (k % 6) {
      case 0:
        out.push_back(v);
        break;
      case 1: {  // on an edge
        const std::size_t i = pick(rng);
        out.push_back(vertices[i] +
                      (vertices[(i + 1) % vertices.size()] - vertices[i]) * unit(rng));
        break;
      }
      case 2:
        out.push_back({std::nextafter(v.x, INFINITY), std::nextafter(v.y, -INFINITY)});
        break;
      case 3:
        out.push_back({coordinate(rng), v.y});
        break;
      case 4:
        out.push_back(v + (w - v) * unit(rng));
        break;
      default:
        out.push_back({coordinate(rng), coordinate(rng)});
    }
  }
  return out;
}

TEST(VisibilityRouterFan, HoldsTheEdgesOfTheStraightforwardConstruction) {
  test::Rng rng(5253);
  std::size_t binned = 0, near = 0;
  for (int k = 0; k < 12; ++k) {
    const std::vector<Ring> rings = area(rng, k);
    const VisibilityRouter router(rings);
    for (const Point2 a : points(rng, rings, 120)) {
      const auto fan = Probe::fan_of(router, a);
      const ReferenceFan truth = reference_fan(router, rings, a);
      SCOPED_TRACE(::testing::Message() << "area " << k << " from (" << a.x << ", " << a.y << ")");
      ASSERT_EQ(fan.start, truth.start);
      ASSERT_EQ(Probe::items(fan), truth.items);
      ASSERT_EQ(fan.near, truth.near);
      binned += fan.start.back();
      near += fan.near.size();
    }
  }
  // Both kinds of edge are there (points on edges and at vertices have near edges).
  EXPECT_GT(binned, 100000u);
  EXPECT_GT(near, 300u);
}

// Vertices whose diamond angle from the point is 4 exactly (the end of the turn: a hair below
// the point's level, far to its right), the greatest an edge's lesser end can have: its range of
// bins starts at the last bin, not past it (fan_of() wraps only negative bins).
TEST(VisibilityRouterFan, HoldsTheEdgesOfTheStraightforwardConstructionAtTheEndOfTheTurn) {
  test::Rng rng(5256);
  std::size_t at_end = 0;
  for (int k = 0; k < 8; ++k) {
    const std::vector<Ring> rings = area(rng, k);
    const VisibilityRouter router(rings);
    for (const Ring& ring : rings)
      for (std::size_t i = 0; i < ring.size(); i += 3) {
        const Point2 v = ring[i];
        for (const double left_m : {1e3, 1e5}) {
          const Point2 a{v.x - left_m, std::nextafter(v.y, INFINITY)};
          at_end += reference_diamond(v.x - a.x, v.y - a.y) == 4.0;
          const auto fan = Probe::fan_of(router, a);
          const ReferenceFan truth = reference_fan(router, rings, a);
          SCOPED_TRACE(::testing::Message()
                       << "area " << k << " from (" << a.x << ", " << a.y << ")");
          ASSERT_EQ(fan.start, truth.start);
          ASSERT_EQ(Probe::items(fan), truth.items);
          ASSERT_EQ(fan.near, truth.near);
        }
      }
  }
  EXPECT_GT(at_end, 100u);
}

// The near edges (asked for every leg) are found round the point, not by a test of every edge:
// points at distances from an edge on either side of the near distance (near_m) and of the box
// rule's (2 near_m; diagonally off a vertex, where an edge's box is nearer than the edge), one
// after another from one router (nothing of one point's fan left in the next): the fan is the
// straightforward construction's.
TEST(VisibilityRouterFan, NearEdgesAreFoundAtTheNearDistance) {
  test::Rng rng(5255);
  std::size_t near = 0, beyond = 0;
  for (int k = 0; k < 8; ++k) {
    const std::vector<Ring> rings = area(rng, k);
    const VisibilityRouter router(rings);
    std::vector<std::pair<Point2, Point2>> edges;
    for (const Ring& ring : rings)
      for (std::size_t i = 0; i < ring.size(); ++i)
        edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
    std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int q = 0; q < 60; ++q) {
      const auto [p, r] = edges[pick(rng)];
      const Point2 along = r - p;
      const double length = std::hypot(along.x, along.y);
      const Point2 normal{-along.y / length, along.x / length};
      const Point2 on = q % 2 ? p + along * unit(rng) : p;  // on the edge, or at its vertex
      const Point2 off = q % 2 ? normal : Point2{std::sqrt(0.5), std::sqrt(0.5)};
      const double near_m =
          1e-6 * (1 + std::max({Probe::extent_m(router), std::abs(on.x), std::abs(on.y)}));
      for (const double times : {0.3, 0.9, 0.999, 1.001, 1.1, 1.9, 1.999, 2.001, 2.1, 3.0}) {
        for (const double side : {1.0, -1.0}) {
          const Point2 a = on + off * (side * times * near_m);
          const auto fan = Probe::fan_of(router, a);
          const ReferenceFan truth = reference_fan(router, rings, a);
          SCOPED_TRACE(::testing::Message() << "area " << k << " from (" << a.x << ", " << a.y
                                            << "), " << times << " near_m off an edge");
          ASSERT_EQ(fan.near, truth.near);
          ASSERT_EQ(fan.start, truth.start);
          ASSERT_EQ(Probe::items(fan), truth.items);
          (times < 1 ? near : beyond) += fan.near.size();
        }
      }
    }
  }
  // Edges within the near distance are near; some beyond it too (other edges of the corner).
  EXPECT_GT(near, 2000u);
  EXPECT_GT(beyond, 100u);
}

// The largest absolute coordinate of the rings' vertices (the router's extent: a fan is asked for
// legs to points within it only).
double largest_coordinate(const std::vector<Ring>& rings) {
  double extent = 0;
  for (const Ring& ring : rings)
    for (const Point2& v : ring) extent = std::max({extent, std::abs(v.x), std::abs(v.y)});
  return extent;
}

TEST(VisibilityRouterFan, LegsThroughAFanAreMeasuredAsOverEveryEdge) {
  test::Rng rng(5254);
  std::size_t seen = 0, hidden = 0;
  for (int k = 0; k < 12; ++k) {
    const std::vector<Ring> rings = area(rng, k);
    const test::BruteArea brute(rings);
    const VisibilityRouter router(rings);
    const double extent = largest_coordinate(rings);
    const std::vector<Point2> froms = points(rng, rings, 40), tos = points(rng, rings, 120);
    for (const Point2 a : froms) {
      const auto fan = Probe::fan_of(router, a);
      for (const Point2 b : tos) {
        // A fan is asked for legs to points within the area's extent only (path()).
        if (std::max(std::abs(b.x), std::abs(b.y)) > extent) continue;
        SCOPED_TRACE(::testing::Message() << "area " << k << " (" << a.x << ", " << a.y << ") - ("
                                          << b.x << ", " << b.y << ")");
        ASSERT_EQ(Probe::outside_m(router, a, b, fan), brute.length_outside(a, b));
        const bool visible = Probe::visible(router, a, b, fan);
        ASSERT_EQ(visible, brute.visible(a, b));
        (visible ? seen : hidden) += 1;
      }
    }
  }
  // Both answers are asked about often.
  EXPECT_GT(seen, 5000u);
  EXPECT_GT(hidden, 5000u);
}

// A fan's point is inside (an odd number of crossings, on no edge: a leg from it that meets no
// edge is inside without a ray cast at its middle) exactly where locate_point() over the rings
// says so; legs from such points, most meeting no edge, measure as over every edge (the
// brute-force area), bit for bit.
TEST(VisibilityRouterFan, APointInsideIsInsideByItsRingsAndItsClearLegsAreInside) {
  test::Rng rng(5257);
  std::size_t inside = 0, not_inside = 0, clear = 0;
  for (int k = 0; k < 8; ++k) {
    const std::vector<Ring> rings = area(rng, k);
    const test::BruteArea brute(rings);
    const VisibilityRouter router(rings);
    const double extent = largest_coordinate(rings);
    const std::vector<Point2> tos = points(rng, rings, 60);
    for (const Point2 a : points(rng, rings, 240)) {
      const auto fan = Probe::fan_of(router, a);
      bool on_boundary = false;
      int containing = 0;
      for (const Ring& ring : rings) {
        const Containment where = locate_point(a, ring);
        on_boundary |= where == Containment::on_boundary;
        containing += where == Containment::inside;
      }
      SCOPED_TRACE(::testing::Message() << "area " << k << " from (" << a.x << ", " << a.y << ")");
      ASSERT_EQ(fan.inside, !on_boundary && containing % 2 == 1);
      if (!fan.inside) {
        ++not_inside;
        continue;
      }
      ++inside;
      for (const Point2 b : tos) {
        if (std::max(std::abs(b.x), std::abs(b.y)) > extent) continue;
        const double outside_m = brute.length_outside(a, b);
        ASSERT_EQ(Probe::outside_m(router, a, b, fan), outside_m) << "to " << b.x << ", " << b.y;
        ASSERT_EQ(Probe::visible(router, a, b, fan), brute.visible(a, b));
        clear += outside_m == 0;
      }
    }
  }
  EXPECT_GT(inside, 300u);
  EXPECT_GT(not_inside, 300u);
  EXPECT_GT(clear, 5000u);
}

}  // namespace
}  // namespace swath::geometry

namespace swath::geometry {
namespace {

// The search going on from a node skips the open nodes whose bit in the node's row of the
// known-hidden bits is set, without looking at the table: a bit set where the pair sees each
// other would leave a leg out of the search, a bit missing only costs a leg measured. After many
// paths (with the corner allowance, where the search uses the bits) on random areas with holes,
// every bit is set exactly where the table says the pair is hidden, in both rows; and a fair
// share of the pairs has been asked, both ways (paths between points inside: one to a point
// outside is straight, no pair asked).
TEST(VisibilityRouterHiddenBits, AreSetExactlyWhereTheTableSaysHidden) {
  test::Rng rng(5252);
  std::size_t hidden = 0, seen = 0;
  for (int area = 0; area < 6; ++area) {
    std::vector<Ring> rings{test::random_field_polygon(rng, std::size_t(40) << area % 3, 500)};
    for (int h = 0; h < 4 + 3 * area; ++h) {
      const double x = -300 + 75.0 * (h % 8), y = -300 + 75.0 * (h / 8);
      rings.push_back({{x, y}, {x, y + 20}, {x + 25, y + 20}, {x + 25, y}});
    }
    const VisibilityRouter router(rings, Routing::routed, 2.0);
    // Ends on the outline (as lanes end), where paths bend round corners: a path to a point
    // outside is the straight leg, without a search.
    std::uniform_int_distribution<std::size_t> vertex(0, rings[0].size() - 1);
    for (int q = 0; q < 1000; ++q) {
      const Point2 a = rings[0][vertex(rng)];
      router.path(a, rings[0][vertex(rng)]);
    }
    const std::size_t n = Probe::nodes(router);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        if (i == j) continue;
        const signed char known = Probe::known(router, i, j);
        ASSERT_EQ(known, Probe::known(router, j, i)) << i << " " << j;
        ASSERT_EQ(Probe::hidden_bit(router, i, j), known == 0)
            << "area " << area << ": " << i << " " << j;
        hidden += known == 0;
        seen += known == 1;
      }
  }
  EXPECT_GT(hidden, 1000u);
  EXPECT_GT(seen, 1000u);
}

}  // namespace
}  // namespace swath::geometry
